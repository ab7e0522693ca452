#include "engine/scene/model.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/work_counter.h"

namespace eng {

const char* textureWrapName(TextureWrap wrap) {
  return wrap == TextureWrap::ClampToEdge ? "clamp-to-edge" : wrap == TextureWrap::MirroredRepeat ? "mirrored-repeat" : "repeat";
}

std::string describeSampling(const TextureSampling& s) {
  auto filter = [](TextureFilter f) { return f == TextureFilter::Nearest ? "nearest" : "linear"; };
  std::string out = std::string(textureWrapName(s.wrapS)) + " x " + textureWrapName(s.wrapT) + ", magnified " +
                    filter(s.magFilter) + ", minified " + filter(s.minFilter);
  out += s.mipmaps ? std::string(", ") + filter(s.mipFilter) + " between mipmaps" : ", no mipmaps";
  return out;
}

glm::mat4 Node::localTransform() const {
  if (hasMatrix) return matrix;
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translation);
  m *= glm::mat4_cast(rotation);
  return glm::scale(m, scale);
}

float Animation::duration() const {
  float d = 0.0f;
  for (const WeightsChannel& c : channels)
    if (!c.times.empty()) d = std::max(d, c.times.back());
  for (const NodeChannel& c : nodeChannels)
    if (!c.times.empty()) d = std::max(d, c.times.back());
  return d;
}

std::vector<int> Model::firstNodeOfEachMesh() const {
  std::vector<int> first(meshes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const int mesh = nodes[i].mesh;
    if (mesh >= 0 && size_t(mesh) < meshes.size() && first[size_t(mesh)] < 0) first[size_t(mesh)] = int(i);
  }
  return first;
}

glm::mat4 Model::worldTransform(int node) const {
  glm::mat4 m(1.0f);
  // The loader rejects cycles; the step bound keeps a hand-built bad graph finite.
  for (size_t steps = 0; node >= 0 && node < static_cast<int>(nodes.size()) && steps <= nodes.size(); ++steps) {
    m = nodes[node].localTransform() * m;
    node = nodes[node].parent;
    countWork();  // O(depth) per call: many nodes want restWorldMatrices (skeleton_pose.h)
  }
  return m;
}

Aabb Model::bounds() const {
  Aabb box;
  // Top-down with the parent's world matrix on the stack: linear in the node count.
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
  std::vector<bool> seen(nodes.size(), false);
  while (!stack.empty()) {
    const auto [n, parentWorld] = stack.back();
    stack.pop_back();
    if (n < 0 || n >= static_cast<int>(nodes.size()) || seen[n]) continue;
    seen[n] = true;
    const Node& node = nodes[n];
    const glm::mat4 world = parentWorld * node.localTransform();
    if (node.mesh >= 0 && node.mesh < static_cast<int>(meshes.size()))
      for (const Primitive& prim : meshes[node.mesh].primitives)
        for (const glm::vec3& p : prim.positions) box.extend(glm::vec3(world * glm::vec4(p, 1.0f)));
    for (int c : node.children) stack.emplace_back(c, world);
  }
  return box;
}

size_t Model::totalVertexCount() const {
  size_t n = 0;
  for (const Mesh& mesh : meshes)
    for (const Primitive& prim : mesh.primitives) n += prim.vertexCount();
  return n;
}

void turnAtRoots(Model& model, const glm::quat& turn) {
  for (Node& node : model.nodes) {
    if (node.parent >= 0) continue;
    if (node.hasMatrix) node.matrix = glm::mat4_cast(turn) * node.matrix;
    else node.rotation = turn * node.rotation, node.translation = turn * node.translation;
  }
}

}  // namespace eng
