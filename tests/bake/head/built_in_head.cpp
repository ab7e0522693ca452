#include "tests/bake/head/built_in_head.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tests/common/test_support.h"

namespace head_testing {

const bake::HeadRigSpec& builtInSpec() {
  static const bake::HeadRigSpec spec = [] {
    auto loaded = bake::loadHeadRigSpec(testing_support::sourceDir() / "data" / "head_landmarks.json");
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded).value();
  }();
  return spec;
}

const bake::GeneratedHead& builtInHead() {
  static const bake::GeneratedHead head = [] {
    auto generated = bake::generateHead(builtInSpec());
    if (!generated) throw std::runtime_error(generated.error().message);
    return std::move(generated).value();
  }();
  return head;
}

const eng::Mesh& headMesh(const eng::Model& model) {
  for (const eng::Mesh& m : model.meshes)
    if (m.name == "Head") return m;
  throw std::runtime_error("model has no mesh named Head");
}

const eng::Primitive& headPrimitive(const eng::Model& model, bake::HeadPrimitive p) {
  return headMesh(model).primitives.at(static_cast<size_t>(p));
}

int targetIndex(const eng::Mesh& mesh, const std::string& name) {
  for (size_t i = 0; i < mesh.targetNames.size(); ++i)
    if (mesh.targetNames[i] == name) return static_cast<int>(i);
  return -1;
}

glm::vec3 landmark(const bake::GeneratedHead& head, const std::string& name) {
  const int i = head.landmarks.find(name);
  if (i < 0) throw std::runtime_error("no landmark " + name);
  return head.landmarks.positions[static_cast<size_t>(i)];
}

std::vector<glm::vec3> morphed(const eng::Primitive& prim, int target, float weight) {
  std::vector<glm::vec3> out = prim.positions;
  if (target < 0) return out;
  const eng::MorphTarget& t = prim.targets.at(static_cast<size_t>(target));
  for (size_t v = 0; v < out.size(); ++v) out[v] += weight * t.positions[v];
  return out;
}

size_t nearestVertex(const std::vector<glm::vec3>& positions, const glm::vec3& p) {
  size_t best = 0;
  float bestDistance = std::numeric_limits<float>::max();
  for (size_t v = 0; v < positions.size(); ++v) {
    const float d = glm::length(positions[v] - p);
    if (d < bestDistance) {
      bestDistance = d;
      best = v;
    }
  }
  return best;
}

eng::Primitive eyeballInHeadSpace(const eng::Model& model, int index) {
  const std::string name = index == 0 ? "EyeLeft" : "EyeRight";
  for (const eng::Node& node : model.nodes) {
    if (node.mesh < 0 || model.meshes[size_t(node.mesh)].name != name) continue;
    eng::Primitive prim = model.meshes[size_t(node.mesh)].primitives.at(0);
    const glm::mat4 world = model.worldTransform(int(&node - model.nodes.data()));
    for (glm::vec3& p : prim.positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
    return prim;
  }
  throw std::runtime_error("model has no node drawing a mesh named " + name);
}

Eyeball eyeball(const eng::Model& model, int index) {
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : eyeballInHeadSpace(model, index).positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const float radius = (hi.x - lo.x) * 0.5f;
  return {glm::vec3((lo.x + hi.x) * 0.5f, (lo.y + hi.y) * 0.5f, lo.z + radius), radius};
}

namespace {

// Depth at (x, y) of the triangle a b c seen along -Z, if (x, y) lies in it.
std::optional<float> triangleHitZ(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float x, float y) {
  const float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (std::abs(area) < 1e-14f) return std::nullopt;
  const float w0 = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area;
  const float w1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
  const float w2 = 1.0f - w0 - w1;
  if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) return std::nullopt;
  return a.z * w0 + b.z * w1 + c.z * w2;
}

}  // namespace

std::optional<float> frontHitZ(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices, float x,
                               float y) {
  std::optional<float> best;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::optional<float> z =
        triangleHitZ(positions[indices[t]], positions[indices[t + 1]], positions[indices[t + 2]], x, y);
    if (z && (!best || *z > *best)) best = z;
  }
  return best;
}

FrontView::FrontView(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices)
    : positions_(positions), indices_(indices), buckets_(size_t(kCells * kCells)) {
  glm::vec2 hi(-std::numeric_limits<float>::max());
  lo_ = glm::vec2(std::numeric_limits<float>::max());
  for (uint32_t i : indices) {
    lo_ = glm::min(lo_, glm::vec2(positions[i]));
    hi = glm::max(hi, glm::vec2(positions[i]));
  }
  cellSize_ = glm::max((hi - lo_) / float(kCells), glm::vec2(1e-9f));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3 &a = positions[indices[t]], &b = positions[indices[t + 1]], &c = positions[indices[t + 2]];
    const int x0 = cellOf(std::min({a.x, b.x, c.x}), lo_.x, cellSize_.x), x1 = cellOf(std::max({a.x, b.x, c.x}), lo_.x, cellSize_.x);
    const int y0 = cellOf(std::min({a.y, b.y, c.y}), lo_.y, cellSize_.y), y1 = cellOf(std::max({a.y, b.y, c.y}), lo_.y, cellSize_.y);
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx) buckets_[size_t(cy * kCells + cx)].push_back(uint32_t(t));
  }
}

int FrontView::cellOf(float v, float lo, float size) const {
  return std::clamp(int(std::floor((v - lo) / size)), 0, kCells - 1);
}

std::optional<float> FrontView::hitZ(float x, float y) const {
  std::optional<float> best;
  const std::vector<uint32_t>& bucket =
      buckets_[size_t(cellOf(y, lo_.y, cellSize_.y) * kCells + cellOf(x, lo_.x, cellSize_.x))];
  for (uint32_t t : bucket) {
    const std::optional<float> z =
        triangleHitZ(positions_[indices_[t]], positions_[indices_[t + 1]], positions_[indices_[t + 2]], x, y);
    if (z && (!best || *z > *best)) best = z;
  }
  return best;
}

}  // namespace head_testing
