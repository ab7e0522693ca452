#include "engine/scene/model_check.h"

#include <cmath>
#include <string>

namespace eng {
namespace {

std::string sizes(size_t have, const char* what, size_t want) {
  return std::to_string(have) + " " + what + " for " + std::to_string(want) + " vertices";
}

template <class Vec>
bool allFinite(const std::vector<Vec>& values) {
  for (const Vec& v : values)
    for (int c = 0; c < Vec::length(); ++c)
      if (!std::isfinite(v[c])) return false;
  return true;
}

Result<void> checkPrimitive(const Primitive& p, size_t targetCount, size_t materialCount, const std::string& label) {
  const size_t n = p.vertexCount();
  if (n == 0) return makeError(ErrorKind::Malformed, label + " has no vertices");
  if (p.normals.size() != n && !p.normals.empty()) return makeError(ErrorKind::Malformed, label + " has " + sizes(p.normals.size(), "normals", n));
  if (!p.texcoords.empty() && p.texcoords.size() != n)
    return makeError(ErrorKind::Malformed, label + " has " + sizes(p.texcoords.size(), "texcoords", n));
  if (!p.tangents.empty() && p.tangents.size() != n)
    return makeError(ErrorKind::Malformed, label + " has " + sizes(p.tangents.size(), "tangents", n));
  if (p.indices.size() % 3 != 0)
    return makeError(ErrorKind::Malformed, label + " has " + std::to_string(p.indices.size()) + " indices, not a multiple of 3");
  for (size_t i = 0; i < p.indices.size(); ++i)
    if (p.indices[i] >= n)
      return makeError(ErrorKind::Malformed, label + ": index " + std::to_string(p.indices[i]) + " at position " + std::to_string(i) +
                       " is out of range of " + std::to_string(n) + " vertices");
  if (p.joints.size() != p.jointWeights.size() || p.joints.size() % n != 0)
    return makeError(ErrorKind::Malformed, label + " has " + std::to_string(p.joints.size()) + " joint groups and " +
                     std::to_string(p.jointWeights.size()) + " weight groups for " + std::to_string(n) + " vertices");
  if (!allFinite(p.jointWeights)) return makeError(ErrorKind::Malformed, label + " has non-finite joint weights");
  if (p.material < -1 || (p.material >= 0 && static_cast<size_t>(p.material) >= materialCount))
    return makeError(ErrorKind::Malformed, label + " uses material " + std::to_string(p.material) + " of " + std::to_string(materialCount));
  if (!allFinite(p.positions) || !allFinite(p.normals) || !allFinite(p.texcoords) || !allFinite(p.tangents))
    return makeError(ErrorKind::Malformed, label + " has non-finite vertex data");
  if (p.targets.size() != targetCount)
    return makeError(ErrorKind::Malformed, label + " has " + std::to_string(p.targets.size()) + " morph targets, its mesh names " +
                     std::to_string(targetCount));
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const MorphTarget& target = p.targets[t];
    const std::string tl = label + " target " + std::to_string(t);
    if (!target.positions.empty() && target.positions.size() != n)
      return makeError(ErrorKind::Malformed, tl + " has " + sizes(target.positions.size(), "position deltas", n));
    if (!target.normals.empty() && target.normals.size() != n)
      return makeError(ErrorKind::Malformed, tl + " has " + sizes(target.normals.size(), "normal deltas", n));
    if (!target.tangents.empty() && target.tangents.size() != n)
      return makeError(ErrorKind::Malformed, tl + " has " + sizes(target.tangents.size(), "tangent deltas", n));
    if (!allFinite(target.positions) || !allFinite(target.normals) || !allFinite(target.tangents))
      return makeError(ErrorKind::Malformed, tl + " has non-finite deltas");
  }
  return {};
}

}  // namespace

Result<void> checkModel(const Model& model) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const Image& img = model.images[i];
    if (img.width <= 0 || img.height <= 0 ||
        img.rgba8.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4)
      return makeError(ErrorKind::Malformed, "image " + std::to_string(i) + " is " + std::to_string(img.width) + "x" +
                       std::to_string(img.height) + " with " + std::to_string(img.rgba8.size()) + " RGBA8 bytes");
  }
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const Material& mat = model.materials[i];
    const std::string label = "material " + std::to_string(i);
    if (mat.baseColorImage < -1 || mat.baseColorImage >= static_cast<int>(model.images.size()))
      return makeError(ErrorKind::Malformed, label + " uses image " + std::to_string(mat.baseColorImage) + " of " +
                       std::to_string(model.images.size()));
    for (size_t l = 0; l < mat.detailLayers.size(); ++l)
      if (mat.detailLayers[l].image < 0 || mat.detailLayers[l].image >= static_cast<int>(model.images.size()))
        return makeError(ErrorKind::Malformed, label + " detail layer " + std::to_string(l) + " uses image " +
                         std::to_string(mat.detailLayers[l].image) + " of " + std::to_string(model.images.size()));
  }
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    const std::string label = "mesh " + std::to_string(m) + (mesh.name.empty() ? "" : " '" + mesh.name + "'");
    if (mesh.defaultWeights.size() != mesh.targetNames.size())
      return makeError(ErrorKind::Malformed, label + " has " + std::to_string(mesh.defaultWeights.size()) + " default weights for " +
                       std::to_string(mesh.targetNames.size()) + " targets");
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      if (auto ok = checkPrimitive(mesh.primitives[p], mesh.targetNames.size(), model.materials.size(),
                                   label + " primitive " + std::to_string(p));
          !ok)
        return ok;
  }
  const int nodeCount = static_cast<int>(model.nodes.size());
  for (int i = 0; i < nodeCount; ++i) {
    const Node& node = model.nodes[i];
    const std::string label = "node " + std::to_string(i);
    if (node.mesh < -1 || node.mesh >= static_cast<int>(model.meshes.size()))
      return makeError(ErrorKind::Malformed, label + " uses mesh " + std::to_string(node.mesh) + " of " + std::to_string(model.meshes.size()));
    for (int c : node.children)
      if (c < 0 || c >= nodeCount || model.nodes[c].parent != i)
        return makeError(ErrorKind::Malformed, label + " lists child " + std::to_string(c) + " whose parent is not " + std::to_string(i));
    if (node.parent >= nodeCount) return makeError(ErrorKind::Malformed, label + " has parent " + std::to_string(node.parent));
    if (node.skin < -1 || node.skin >= static_cast<int>(model.skins.size()))
      return makeError(ErrorKind::Malformed, label + " uses skin " + std::to_string(node.skin) + " of " + std::to_string(model.skins.size()));
    const glm::vec4 trs[] = {glm::vec4(node.translation, 0.0f), glm::vec4(node.scale, 0.0f),
                             glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w),
                             node.matrix[0], node.matrix[1], node.matrix[2], node.matrix[3]};
    for (const glm::vec4& v : trs)
      if (glm::any(glm::isnan(v)) || glm::any(glm::isinf(v))) return makeError(ErrorKind::Malformed, label + " has a non-finite transform");
  }
  for (int root : model.roots)
    if (root < 0 || root >= nodeCount || model.nodes[root].parent != -1)
      return makeError(ErrorKind::Malformed, "root " + std::to_string(root) + " is not a parentless node");
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const Skin& skin = model.skins[s];
    const std::string label = "skin " + std::to_string(s);
    for (int j : skin.joints)
      if (j < 0 || j >= nodeCount) return makeError(ErrorKind::Malformed, label + " has joint node " + std::to_string(j) + " of " + std::to_string(nodeCount));
    if (!skin.inverseBindMatrices.empty() && skin.inverseBindMatrices.size() != skin.joints.size())
      return makeError(ErrorKind::Malformed, label + " has " + std::to_string(skin.inverseBindMatrices.size()) + " inverse bind matrices for " +
                       std::to_string(skin.joints.size()) + " joints");
    for (const glm::mat4& m : skin.inverseBindMatrices)
      for (int c = 0; c < 4; ++c)
        if (glm::any(glm::isnan(m[c])) || glm::any(glm::isinf(m[c])))
          return makeError(ErrorKind::Malformed, label + " has a non-finite inverse bind matrix");
  }
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t c = 0; c < model.animations[a].nodeChannels.size(); ++c) {
      const NodeChannel& ch = model.animations[a].nodeChannels[c];
      const std::string label = "animation " + std::to_string(a) + " node channel " + std::to_string(c);
      if (ch.node < 0 || ch.node >= nodeCount) return makeError(ErrorKind::Malformed, label + " targets node " + std::to_string(ch.node));
      const size_t perKey = ch.components() * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (ch.times.empty() || ch.values.size() != ch.times.size() * perKey)
        return makeError(ErrorKind::Malformed, label + " has " + std::to_string(ch.values.size()) + " values for " +
                         std::to_string(ch.times.size()) + " keys of " + std::to_string(perKey));
    }
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t c = 0; c < model.animations[a].channels.size(); ++c) {
      const WeightsChannel& ch = model.animations[a].channels[c];
      const std::string label = "animation " + std::to_string(a) + " channel " + std::to_string(c);
      if (ch.node < 0 || ch.node >= nodeCount || model.nodes[ch.node].mesh != ch.mesh || ch.mesh < 0)
        return makeError(ErrorKind::Malformed, label + " targets node " + std::to_string(ch.node) + " / mesh " + std::to_string(ch.mesh) +
                         ", which do not match");
      if (ch.targetCount != model.meshes[ch.mesh].targetNames.size())
        return makeError(ErrorKind::Malformed, label + " has " + std::to_string(ch.targetCount) + " weights per key, the mesh has " +
                         std::to_string(model.meshes[ch.mesh].targetNames.size()) + " targets");
      const size_t perKey = ch.targetCount * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (ch.times.empty() || ch.values.size() != ch.times.size() * perKey)
        return makeError(ErrorKind::Malformed, label + " has " + std::to_string(ch.values.size()) + " values for " +
                         std::to_string(ch.times.size()) + " keys of " + std::to_string(perKey));
    }
  return {};
}

}  // namespace eng
