#include "engine/scene/weights.h"

#include <string>

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
  if (mesh < 0 || mesh >= static_cast<int>(offsets_.size())) return total();
  return offsets_[mesh];
}

uint32_t WeightLayout::count(int mesh) const {
  if (mesh < 0 || mesh >= meshCount()) return 0;
  return offsets_[mesh + 1] - offsets_[mesh];
}

uint32_t WeightLayout::total() const { return offsets_.back(); }

std::vector<std::string> WeightLayout::names() const { return names_; }

int WeightLayout::find(int mesh, std::string_view name) const {
  const uint32_t begin = offset(mesh), end = offset(mesh + 1);
  for (uint32_t i = begin; i < end; ++i)
    if (names_[i] == name) return static_cast<int>(i);
  return -1;
}

namespace {

Error wrongSize(const char* function, size_t size, uint32_t total) {
  return makeError(ErrorKind::InvalidArgument, std::string(function) + ": weights has " + std::to_string(size) +
                                                   " entries, layout total is " + std::to_string(total));
}

}  // namespace

Result<int> WeightLayout::setByName(std::span<float> weights, std::string_view name, float value) const {
  if (weights.size() != total()) return wrongSize("WeightLayout::setByName", weights.size(), total());
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

Result<std::span<const float>> WeightLayout::meshWeights(std::span<const float> weights, int mesh) const {
  if (weights.size() != total()) return wrongSize("WeightLayout::meshWeights", weights.size(), total());
  if (mesh < 0 || mesh >= meshCount())
    return makeError(ErrorKind::InvalidArgument, "WeightLayout::meshWeights: mesh " + std::to_string(mesh) +
                                                     " outside 0.." + std::to_string(meshCount() - 1));
  return weights.subspan(offsets_[mesh], count(mesh));
}

}  // namespace eng
