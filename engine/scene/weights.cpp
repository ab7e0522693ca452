#include "engine/scene/weights.h"

#include <stdexcept>

namespace eng {

WeightLayout::WeightLayout(const Model& model) {
  offsets_.reserve(model.meshes.size() + 1);
  uint32_t running = 0;
  for (const Mesh& mesh : model.meshes) {
    offsets_.push_back(running);
    running += static_cast<uint32_t>(mesh.targetNames.size());
    names_.insert(names_.end(), mesh.targetNames.begin(), mesh.targetNames.end());
    for (size_t i = 0; i < mesh.targetNames.size(); ++i)
      defaults_.push_back(i < mesh.defaultWeights.size() ? mesh.defaultWeights[i] : 0.0f);
  }
  offsets_.push_back(running);
}

uint32_t WeightLayout::offset(int mesh) const {
  if (mesh < 0 || mesh >= static_cast<int>(offsets_.size()))
    throw std::out_of_range("WeightLayout::offset: mesh " + std::to_string(mesh) + " outside 0.." +
                            std::to_string(offsets_.size() - 1));
  return offsets_[mesh];
}

uint32_t WeightLayout::count(int mesh) const { return offset(mesh + 1) - offset(mesh); }

uint32_t WeightLayout::total() const { return offsets_.back(); }

std::vector<std::string> WeightLayout::names() const { return names_; }

int WeightLayout::find(int mesh, std::string_view name) const {
  const uint32_t begin = offset(mesh), end = offset(mesh + 1);
  for (uint32_t i = begin; i < end; ++i)
    if (names_[i] == name) return static_cast<int>(i);
  return -1;
}

int WeightLayout::setByName(std::span<float> weights, std::string_view name, float value) const {
  if (weights.size() != total())
    throw std::invalid_argument("WeightLayout::setByName: weights has " + std::to_string(weights.size()) +
                                " entries, layout total is " + std::to_string(total()));
  int matched = 0;
  for (int m = 0; m < meshCount(); ++m) {
    const int i = find(m, name);
    if (i >= 0) {
      weights[i] = value;
      ++matched;
    }
  }
  return matched;
}

std::vector<float> WeightLayout::defaults() const { return defaults_; }

std::span<const float> WeightLayout::meshWeights(std::span<const float> weights, int mesh) const {
  if (weights.size() != total())
    throw std::invalid_argument("WeightLayout::meshWeights: weights has " + std::to_string(weights.size()) +
                                " entries, layout total is " + std::to_string(total()));
  return weights.subspan(offset(mesh), count(mesh));
}

}  // namespace eng
