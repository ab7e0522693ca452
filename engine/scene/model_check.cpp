#include "engine/scene/model_check.h"

#include <cmath>
#include <string>

namespace eng {
namespace {

// "mesh 2 'face'": an element by index, and by name where it has one.
std::string named(const char* what, size_t index, const std::string& name) {
  return std::string(what) + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

std::string sizes(size_t have, const char* what, size_t want) {
  return std::to_string(have) + " " + what + " for " + std::to_string(want) + " vertices";
}

// "uses image 7 of 2 images": an index into a list that does not hold it.
std::string usesOf(const char* what, long long index, size_t count, const char* plural) {
  return std::string(" uses ") + what + " " + std::to_string(index) + " of " + std::to_string(count) + " " + plural;
}

Error malformed(const std::string& message) { return makeError(ErrorKind::Malformed, message); }

template <class Vec>
bool allFinite(const std::vector<Vec>& values) {
  for (const Vec& v : values)
    for (int c = 0; c < Vec::length(); ++c)
      if (!std::isfinite(v[c])) return false;
  return true;
}

bool finiteMatrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    if (glm::any(glm::isnan(m[c])) || glm::any(glm::isinf(m[c]))) return false;
  return true;
}

Result<void> checkImages(const Model& model) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const Image& img = model.images[i];
    if (img.width <= 0 || img.height <= 0 ||
        img.rgba8.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4)
      return malformed(named("image", i, img.name) + " is " + std::to_string(img.width) + "x" +
                       std::to_string(img.height) + " with " + std::to_string(img.rgba8.size()) + " RGBA8 bytes");
  }
  return {};
}

Result<void> checkMaterials(const Model& model) {
  const int imageCount = static_cast<int>(model.images.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const Material& mat = model.materials[i];
    const std::string label = named("material", i, mat.name);
    if (mat.baseColorImage < -1 || mat.baseColorImage >= imageCount)
      return malformed(label + " base colour" + usesOf("image", mat.baseColorImage, model.images.size(), "images"));
    for (const MaterialTexture& slot : kMaterialTextures)
      if (mat.*slot.image < -1 || mat.*slot.image >= imageCount)
        return malformed(label + " " + slot.name + usesOf("image", mat.*slot.image, model.images.size(), "images"));
    for (size_t l = 0; l < mat.detailLayers.size(); ++l) {
      const DetailLayer& layer = mat.detailLayers[l];
      if (layer.image < 0 || layer.image >= imageCount)
        return malformed(label + " detail layer " + std::to_string(l) + " '" + layer.target + "'" +
                         usesOf("image", layer.image, model.images.size(), "images"));
    }
  }
  return {};
}

// The per-vertex attributes: lengths that match the positions, finite values.
Result<void> checkVertices(const Primitive& p, const ModelCheck& needs, const std::string& label) {
  const size_t n = p.vertexCount();
  if (n == 0) return malformed(label + " has no vertices");
  if (n > needs.maxVertices)
    return malformed(label + " has " + std::to_string(n) + " vertices, more than the " + std::to_string(needs.maxVertices) +
                     " a primitive may have here");
  if (p.normals.size() != n && (needs.requireNormals || !p.normals.empty()))
    return malformed(label + " has " + sizes(p.normals.size(), "normals", n));
  if (!p.texcoords.empty() && p.texcoords.size() != n) return malformed(label + " has " + sizes(p.texcoords.size(), "texcoords", n));
  if (!p.tangents.empty() && p.tangents.size() != n) return malformed(label + " has " + sizes(p.tangents.size(), "tangents", n));
  if (!p.colors.empty() && p.colors.size() != n) return malformed(label + " has " + sizes(p.colors.size(), "colors", n));
  if (!allFinite(p.positions) || !allFinite(p.normals) || !allFinite(p.texcoords) || !allFinite(p.tangents) ||
      !allFinite(p.colors))
    return malformed(label + " has non-finite vertex data");
  if (p.joints.size() != p.jointWeights.size() || p.joints.size() % n != 0)
    return malformed(label + " has " + std::to_string(p.joints.size()) + " joint groups and " +
                     std::to_string(p.jointWeights.size()) + " weight groups for " + std::to_string(n) + " vertices");
  if (!allFinite(p.jointWeights)) return malformed(label + " has non-finite joint weights");
  return {};
}

Result<void> checkTriangles(const Primitive& p, const ModelCheck& needs, const std::string& label) {
  const size_t n = p.vertexCount();
  if (needs.requireIndices && p.indices.empty()) return malformed(label + " has no indices (drawn as an indexed triangle list)");
  if (p.indices.size() % 3 != 0)
    return malformed(label + " has " + std::to_string(p.indices.size()) + " indices, not a multiple of 3");
  for (size_t i = 0; i < p.indices.size(); ++i)
    if (p.indices[i] >= n)
      return malformed(label + ": index " + std::to_string(p.indices[i]) + " at position " + std::to_string(i) +
                       " is out of range of " + std::to_string(n) + " vertices");
  return {};
}

Result<void> checkTargets(const Primitive& p, size_t targetCount, const std::string& label) {
  const size_t n = p.vertexCount();
  if (p.targets.size() != targetCount)
    return malformed(label + " has " + std::to_string(p.targets.size()) + " morph targets, its mesh names " +
                     std::to_string(targetCount));
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const MorphTarget& target = p.targets[t];
    const std::string tl = label + " target " + std::to_string(t);
    if (!target.positions.empty() && target.positions.size() != n)
      return malformed(tl + " has " + sizes(target.positions.size(), "position deltas", n));
    if (!target.normals.empty() && target.normals.size() != n)
      return malformed(tl + " has " + sizes(target.normals.size(), "normal deltas", n));
    if (!target.tangents.empty() && target.tangents.size() != n)
      return malformed(tl + " has " + sizes(target.tangents.size(), "tangent deltas", n));
    if (!allFinite(target.positions) || !allFinite(target.normals) || !allFinite(target.tangents))
      return malformed(tl + " has non-finite deltas");
  }
  return {};
}

Result<void> checkMeshes(const Model& model, const ModelCheck& needs) {
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    const std::string label = named("mesh", m, mesh.name);
    if (mesh.defaultWeights.size() != mesh.targetNames.size())
      return malformed(label + " has " + std::to_string(mesh.defaultWeights.size()) + " default weights for " +
                       std::to_string(mesh.targetNames.size()) + " targets");
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      const std::string where = label + " primitive " + std::to_string(p);
      if (auto ok = checkVertices(prim, needs, where); !ok) return ok;
      if (auto ok = checkTriangles(prim, needs, where); !ok) return ok;
      if (prim.material < -1 || (prim.material >= 0 && static_cast<size_t>(prim.material) >= model.materials.size()))
        return malformed(where + usesOf("material", prim.material, model.materials.size(), "materials"));
      if (auto ok = checkTargets(prim, mesh.targetNames.size(), where); !ok) return ok;
    }
  }
  return {};
}

// The hierarchy: indices in range, parent and child links that agree, roots
// without a parent, finite transforms.
Result<void> checkNodes(const Model& model) {
  const int nodeCount = static_cast<int>(model.nodes.size());
  for (int i = 0; i < nodeCount; ++i) {
    const Node& node = model.nodes[i];
    const std::string label = named("node", static_cast<size_t>(i), node.name);
    if (node.mesh < -1 || node.mesh >= static_cast<int>(model.meshes.size()))
      return malformed(label + usesOf("mesh", node.mesh, model.meshes.size(), "meshes"));
    for (int c : node.children)
      if (c < 0 || c >= nodeCount || model.nodes[c].parent != i)
        return malformed(label + " lists child " + std::to_string(c) + " whose parent is not " + std::to_string(i) + " (" +
                         std::to_string(nodeCount) + " nodes)");
    if (node.parent >= nodeCount)
      return malformed(label + " has parent " + std::to_string(node.parent) + " of " + std::to_string(nodeCount) + " nodes");
    if (node.skin < -1 || node.skin >= static_cast<int>(model.skins.size()))
      return malformed(label + usesOf("skin", node.skin, model.skins.size(), "skins"));
    const glm::vec4 trs[] = {glm::vec4(node.translation, 0.0f), glm::vec4(node.scale, 0.0f),
                             glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w)};
    for (const glm::vec4& v : trs)
      if (glm::any(glm::isnan(v)) || glm::any(glm::isinf(v))) return malformed(label + " has a non-finite transform");
    if (!finiteMatrix(node.matrix)) return malformed(label + " has a non-finite transform");
  }
  for (int root : model.roots)
    if (root < 0 || root >= nodeCount || model.nodes[root].parent != -1)
      return malformed("root " + std::to_string(root) + " is not a parentless node of " + std::to_string(nodeCount));
  return {};
}

Result<void> checkSkins(const Model& model) {
  const int nodeCount = static_cast<int>(model.nodes.size());
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const Skin& skin = model.skins[s];
    const std::string label = named("skin", s, skin.name);
    for (int j : skin.joints)
      if (j < 0 || j >= nodeCount)
        return malformed(label + " has joint node " + std::to_string(j) + " of " + std::to_string(nodeCount) + " nodes");
    // None means identity (glTF); the loader fills them, a model built in code may not.
    if (!skin.inverseBindMatrices.empty() && skin.inverseBindMatrices.size() != skin.joints.size())
      return malformed(label + " has " + std::to_string(skin.inverseBindMatrices.size()) + " inverse bind matrices for " +
                       std::to_string(skin.joints.size()) + " joints");
    for (const glm::mat4& m : skin.inverseBindMatrices)
      if (!finiteMatrix(m)) return malformed(label + " has a non-finite inverse bind matrix");
  }
  return {};
}

// A channel's keys: some, and as many values as they imply.
Result<void> checkKeys(size_t times, size_t values, size_t perKey, const std::string& label) {
  if (times == 0 || values != times * perKey)
    return malformed(label + " has " + std::to_string(values) + " values for " + std::to_string(times) + " keys of " +
                     std::to_string(perKey));
  return {};
}

Result<void> checkAnimations(const Model& model) {
  const int nodeCount = static_cast<int>(model.nodes.size());
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const Animation& animation = model.animations[a];
    const std::string label = named("animation", a, animation.name);
    for (size_t c = 0; c < animation.nodeChannels.size(); ++c) {
      const NodeChannel& ch = animation.nodeChannels[c];
      const std::string cl = label + " node channel " + std::to_string(c);
      if (ch.node < 0 || ch.node >= nodeCount)
        return malformed(cl + " targets node " + std::to_string(ch.node) + " of " + std::to_string(nodeCount));
      const size_t perKey = ch.components() * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (auto ok = checkKeys(ch.times.size(), ch.values.size(), perKey, cl); !ok) return ok;
    }
    for (size_t c = 0; c < animation.channels.size(); ++c) {
      const WeightsChannel& ch = animation.channels[c];
      const std::string cl = label + " channel " + std::to_string(c);
      if (ch.node < 0 || ch.node >= nodeCount || ch.mesh < 0 || model.nodes[ch.node].mesh != ch.mesh)
        return malformed(cl + " targets node " + std::to_string(ch.node) + " / mesh " + std::to_string(ch.mesh) +
                         ", which do not match");
      const size_t targets = model.meshes[ch.mesh].targetNames.size();
      if (ch.targetCount != targets)
        return malformed(cl + " has " + std::to_string(ch.targetCount) + " weights per key, the mesh has " +
                         std::to_string(targets) + " targets");
      const size_t perKey = ch.targetCount * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (auto ok = checkKeys(ch.times.size(), ch.values.size(), perKey, cl); !ok) return ok;
    }
  }
  return {};
}

}  // namespace

Result<void> checkModel(const Model& model, const ModelCheck& needs) {
  if (auto ok = checkImages(model); !ok) return ok;
  if (auto ok = checkMaterials(model); !ok) return ok;
  if (auto ok = checkMeshes(model, needs); !ok) return ok;
  if (auto ok = checkNodes(model); !ok) return ok;
  if (auto ok = checkSkins(model); !ok) return ok;
  return checkAnimations(model);
}

}  // namespace eng
