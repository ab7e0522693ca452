// GLM's operators inlined here whatever the rest of the program does: left to
// the linker, a call to glm's out-of-line mat4 * mat4 went to the copy some
// large file of the program compiled without inlining its vec4 operators,
// and the joint matrices of 64 skinned characters took 2.2 ms a frame, 0.1 ms
// when the same calls were timed in a program of their own
// (facial bench frames RobotExpressive.glb --instances 64).
#define GLM_FORCE_INLINE
#include "engine/scene/skeleton_pose.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/work_counter.h"

namespace eng {
namespace {

// The channel's value at `time` into out[0..components): keys clamped at both
// ends, rotations slerped (LINEAR) or renormalised (CUBICSPLINE).
void sampleChannel(const NodeChannel& ch, float time, std::array<float, 4>& out) {
  const size_t n = ch.components();
  const size_t keys = ch.times.size();
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  const size_t stride = cubic ? 3 * n : n;
  const size_t valueOffset = cubic ? n : 0;  // in-tangent, value, out-tangent
  auto value = [&](size_t key, size_t c) { return ch.values[key * stride + valueOffset + c]; };
  if (keys == 0 || ch.values.size() < keys * stride) return;
  if (keys == 1 || time <= ch.times.front()) {
    for (size_t c = 0; c < n; ++c) out[c] = value(0, c);
    return;
  }
  if (time >= ch.times.back()) {
    for (size_t c = 0; c < n; ++c) out[c] = value(keys - 1, c);
    return;
  }
  const size_t k = static_cast<size_t>(std::upper_bound(ch.times.begin(), ch.times.end(), time) - ch.times.begin()) - 1;
  const float t0 = ch.times[k], t1 = ch.times[k + 1];
  const float dt = t1 - t0;
  const float u = dt > 0.0f ? (time - t0) / dt : 0.0f;
  switch (ch.interpolation) {
    case Interpolation::Step:
      for (size_t c = 0; c < n; ++c) out[c] = value(k, c);
      return;
    case Interpolation::Linear:
      if (ch.path == NodePath::Rotation) {
        const glm::quat a(value(k, 3), value(k, 0), value(k, 1), value(k, 2));
        const glm::quat b(value(k + 1, 3), value(k + 1, 0), value(k + 1, 1), value(k + 1, 2));
        const glm::quat q = glm::slerp(a, b, u);  // takes the short way round
        out = {q.x, q.y, q.z, q.w};
      } else {
        for (size_t c = 0; c < n; ++c) out[c] = value(k, c) + u * (value(k + 1, c) - value(k, c));
      }
      return;
    case Interpolation::CubicSpline: {
      // glTF 2.0, Appendix C: Hermite spline with tangents scaled by the key interval.
      const float u2 = u * u, u3 = u2 * u;
      const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (size_t c = 0; c < n; ++c) {
        const float outTangent = ch.values[k * stride + 2 * n + c];
        const float inTangent = ch.values[(k + 1) * stride + c];
        out[c] = h00 * value(k, c) + h10 * dt * outTangent + h01 * value(k + 1, c) + h11 * dt * inTangent;
      }
      if (ch.path == NodePath::Rotation) {
        const glm::quat q = glm::normalize(glm::quat(out[3], out[0], out[1], out[2]));
        out = {q.x, q.y, q.z, q.w};
      }
      return;
    }
  }
}

}  // namespace

std::vector<int> sceneMeshNodeIndices(const Model& model) {
  std::vector<int> out;
  std::vector<int> stack(model.roots.rbegin(), model.roots.rend());
  std::vector<bool> seen(model.nodes.size(), false);
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (n < 0 || static_cast<size_t>(n) >= model.nodes.size() || seen[n]) continue;
    seen[n] = true;  // shared children and cycles: once
    const Node& node = model.nodes[n];
    if (node.mesh >= 0 && static_cast<size_t>(node.mesh) < model.meshes.size()) out.push_back(n);
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
  }
  return out;
}

Pose restPose(const Model& model) {
  Pose pose;
  pose.translations.reserve(model.nodes.size());
  pose.rotations.reserve(model.nodes.size());
  pose.scales.reserve(model.nodes.size());
  for (const Node& node : model.nodes) {
    pose.translations.push_back(node.translation);
    pose.rotations.push_back(node.rotation);
    pose.scales.push_back(node.scale);
  }
  return pose;
}

void sampleAnimation(const Animation& animation, float time, Pose& pose) {
  for (const NodeChannel& ch : animation.nodeChannels) {
    if (ch.node < 0 || static_cast<size_t>(ch.node) >= pose.nodeCount()) continue;
    std::array<float, 4> v{0.0f, 0.0f, 0.0f, 1.0f};
    switch (ch.path) {
      case NodePath::Translation:
        v = {pose.translations[ch.node].x, pose.translations[ch.node].y, pose.translations[ch.node].z, 0.0f};
        sampleChannel(ch, time, v);
        pose.translations[ch.node] = glm::vec3(v[0], v[1], v[2]);
        break;
      case NodePath::Rotation: {
        const glm::quat& q = pose.rotations[ch.node];
        v = {q.x, q.y, q.z, q.w};
        sampleChannel(ch, time, v);
        pose.rotations[ch.node] = glm::quat(v[3], v[0], v[1], v[2]);
        break;
      }
      case NodePath::Scale:
        v = {pose.scales[ch.node].x, pose.scales[ch.node].y, pose.scales[ch.node].z, 0.0f};
        sampleChannel(ch, time, v);
        pose.scales[ch.node] = glm::vec3(v[0], v[1], v[2]);
        break;
    }
  }
}

glm::mat4 poseLocalMatrix(const Model& model, const Pose& pose, int node) {
  const Node& n = model.nodes[static_cast<size_t>(node)];
  if (n.hasMatrix || static_cast<size_t>(node) >= pose.nodeCount()) return n.localTransform();
  glm::mat4 m = glm::translate(glm::mat4(1.0f), pose.translations[node]);
  m *= glm::mat4_cast(pose.rotations[node]);
  return glm::scale(m, pose.scales[node]);
}

void poseWorldMatrices(const Model& model, const Pose& pose, std::vector<glm::mat4>& out) {
  const size_t count = model.nodes.size();
  out.assign(count, glm::mat4(1.0f));
  // Depth first from every parentless node, parents before children; each
  // node once (the loader rejects cycles and second parents).
  std::vector<bool> done(count, false);
  std::vector<int> stack;
  for (size_t root = 0; root < count; ++root) {
    if (model.nodes[root].parent >= 0) continue;
    stack.push_back(static_cast<int>(root));
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (n < 0 || static_cast<size_t>(n) >= count || done[n]) continue;
      done[n] = true;
      countWork();
      const int parent = model.nodes[n].parent;
      const glm::mat4 local = poseLocalMatrix(model, pose, n);
      out[n] = parent >= 0 ? out[parent] * local : local;
      for (int c : model.nodes[n].children) stack.push_back(c);
    }
  }
}

bool isInvertible(const glm::mat3& linear) {
  const glm::dmat3 m(linear);
  const double bound = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
  const double det = glm::determinant(m);
  return std::isfinite(det) && bound > 0.0 && std::abs(det) > 1e-6 * bound;
}

std::vector<glm::mat4> restWorldMatrices(const Model& model) {
  std::vector<glm::mat4> world;
  poseWorldMatrices(model, restPose(model), world);
  return world;
}

void skinJointMatrices(const Skin& skin, std::span<const glm::mat4> world, int meshNode, std::vector<glm::mat4>& out) {
  const glm::mat4 toMesh = meshNode >= 0 && static_cast<size_t>(meshNode) < world.size()
                               ? glm::inverse(world[meshNode])
                               : glm::mat4(1.0f);
  out.resize(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    const glm::mat4 jointWorld = node >= 0 && static_cast<size_t>(node) < world.size() ? world[node] : glm::mat4(1.0f);
    const glm::mat4 inverseBind = j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f);
    out[j] = toMesh * jointWorld * inverseBind;
  }
}

}  // namespace eng
