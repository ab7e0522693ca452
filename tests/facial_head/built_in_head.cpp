#include "tests/facial_head/built_in_head.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "tests/common/test_support.h"

namespace head_testing {

const facial::HeadRigSpec& builtInSpec() {
  static const facial::HeadRigSpec spec = [] {
    auto loaded = facial::loadHeadRigSpec(testing_support::sourceDir() / "data" / "head_landmarks.json");
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded).value();
  }();
  return spec;
}

const facial::GeneratedHead& builtInHead() {
  static const facial::GeneratedHead head = [] {
    auto generated = facial::generateHead(builtInSpec());
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

const eng::Primitive& headPrimitive(const eng::Model& model, facial::HeadPrimitive p) {
  return headMesh(model).primitives.at(static_cast<size_t>(p));
}

int targetIndex(const eng::Mesh& mesh, const std::string& name) {
  for (size_t i = 0; i < mesh.targetNames.size(); ++i)
    if (mesh.targetNames[i] == name) return static_cast<int>(i);
  return -1;
}

glm::vec3 landmark(const facial::GeneratedHead& head, const std::string& name) {
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

std::optional<float> frontHitZ(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices, float x,
                               float y) {
  std::optional<float> best;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::vec3 &a = positions[indices[t]], &b = positions[indices[t + 1]], &c = positions[indices[t + 2]];
    const float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::abs(area) < 1e-14f) continue;
    const float w0 = ((b.x - x) * (c.y - y) - (c.x - x) * (b.y - y)) / area;
    const float w1 = ((c.x - x) * (a.y - y) - (a.x - x) * (c.y - y)) / area;
    const float w2 = 1.0f - w0 - w1;
    if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
    const float z = a.z * w0 + b.z * w1 + c.z * w2;
    if (!best || z > *best) best = z;
  }
  return best;
}

}  // namespace head_testing
