// glTF primitives (attributes, indices, morph targets, generated normals) and meshes.
#include "engine/scene/gltf_model_builder.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/gtc/type_ptr.hpp>

#include "engine/scene/gltf_skin_reader.h"
#include "engine/scene/normals.h"

namespace eng {

// Triangle list from the primitive's vertex order (indices or 0..n-1) and mode.
std::vector<uint32_t> GltfModelBuilder::triangulate(const std::vector<uint32_t>& order, int mode) {
  std::vector<uint32_t> tris;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    tris.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(order.size() / 3 * 3));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < order.size(); ++i) {
      // Every other strip triangle is flipped to keep one winding.
      if (i % 2 == 0) tris.insert(tris.end(), {order[i], order[i + 1], order[i + 2]});
      else tris.insert(tris.end(), {order[i + 1], order[i], order[i + 2]});
    }
  } else {  // fan
    for (size_t i = 1; i + 1 < order.size(); ++i) tris.insert(tris.end(), {order[0], order[i], order[i + 1]});
  }
  return tris;
}

template <int N>
Result<std::vector<glm::vec<N, float>>> GltfModelBuilder::readAttribute(int accessor, size_t expectedCount, const std::string& what) {
  auto values = reader_.readVec<N>(accessor, what);
  if (!values) return fail(values.error());
  if (expectedCount != SIZE_MAX && values->size() != expectedCount)
    return fail(what + " has " + std::to_string(values->size()) + " elements, its primitive has " +
                std::to_string(expectedCount) + " vertices");
  return values;
}

// What a primitive of `vertices` vertices makes beyond its accessors (generated
// normals, the 0..n-1 order of a non-indexed primitive, the triangle list,
// normals for each generated-normal target) counts against the decode budget
// too, and is charged before anything is read: an accessor without a
// bufferView declares any count in a few bytes of JSON (zero-filled per the
// spec), and everything made from it is as large.
Result<void> GltfModelBuilder::chargeDerivedData(const tinygltf::Primitive& src, int mode, size_t vertices, const std::string& label) {
  constexpr size_t kVec3 = sizeof(glm::vec3), kIndex = sizeof(uint32_t);
  size_t order = vertices;
  if (src.indices >= 0) {
    auto count = reader_.count(src.indices, label + " indices");
    if (!count) return fail(count.error());
    order = std::min(*count, SIZE_MAX / 64);
  }
  const size_t triangleIndices = mode == TINYGLTF_MODE_TRIANGLES ? order / 3 * 3 : order < 3 ? 0 : 3 * (order - 2);
  size_t bytes = triangleIndices * kIndex + (src.indices >= 0 ? 0 : vertices * kIndex);
  if (src.attributes.count("NORMAL") == 0) {
    const size_t morphedNormals = static_cast<size_t>(std::count_if(
        src.targets.begin(), src.targets.end(), [](const auto& target) { return target.count("POSITION") != 0; }));
    bytes += (1 + std::min(morphedNormals, size_t{1} << 20)) * vertices * kVec3;  // min: no overflow
  }
  auto ok = reader_.charge(bytes, label + " POSITION (accessor " + std::to_string(src.attributes.at("POSITION")) +
                                      ", " + std::to_string(vertices) + " vertices): the normals and indices made for it");
  if (!ok) return fail(ok.error());
  return {};
}

// Returns false (with a warning) for primitives we skip.
Result<bool> GltfModelBuilder::loadPrimitive(int m, int p, Primitive& out, size_t& targetCount, bool& targetCountKnown) {
  const tinygltf::Primitive& src = gltf_.meshes[m].primitives[p];
  const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
  const int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    warn(label + " has mode " + std::to_string(mode) + " (points or lines); skipped");
    return false;
  }
  const auto posIt = src.attributes.find("POSITION");
  if (posIt == src.attributes.end()) {
    warn(label + " has no POSITION attribute; skipped");
    return false;
  }
  if (auto declared = reader_.count(posIt->second, label + " POSITION"); !declared) {
    return fail(declared.error());
  } else if (*declared > UINT32_MAX) {
    return fail(label + " has " + std::to_string(*declared) + " vertices, more than 32-bit indices address", ErrorKind::TooLarge);
  } else if (auto ok = chargeDerivedData(src, mode, *declared, label); !ok) {
    return ok.error();
  }
  auto positions = readAttribute<3>(posIt->second, SIZE_MAX, label + " POSITION");
  if (!positions) return positions.error();
  out.positions = std::move(*positions);
  if (out.positions.empty()) {
    warn(label + " has no vertices; skipped");
    return false;
  }
  if (auto ok = readVertexAttributes(src, label, out); !ok) return ok.error();
  const bool generatedNormals = out.normals.empty();
  if (auto ok = readTriangles(src, mode, label, out); !ok) return ok.error();
  if (generatedNormals) out.normals = computeSmoothNormals(out.positions, out.indices);
  assignMaterial(src, label, out);

  if (!targetCountKnown) {
    targetCount = src.targets.size();
    targetCountKnown = true;
  } else if (src.targets.size() != targetCount) {
    return fail(label + " has " + std::to_string(src.targets.size()) + " morph targets, the mesh's other primitives have " +
                std::to_string(targetCount));
  }
  if (auto ok = readMorphTargets(src, label, generatedNormals, out); !ok) return ok.error();
  return true;
}

Result<void> GltfModelBuilder::readVertexAttributes(const tinygltf::Primitive& src, const std::string& label,
                                                    Primitive& out) {
  const size_t n = out.positions.size();
  if (auto it = src.attributes.find("NORMAL"); it != src.attributes.end()) {
    auto normals = readAttribute<3>(it->second, n, label + " NORMAL");
    if (!normals) return normals.error();
    out.normals = std::move(*normals);
  }
  {
    // The set the material's base colour reads (a lightmapped or
    // atlas-packed avatar may put it on TEXCOORD_1).
    const bool knownMaterial = src.material >= 0 && static_cast<size_t>(src.material) < baseColorUvs_.size();
    std::string set = "TEXCOORD_" + std::to_string(knownMaterial ? baseColorUvs_[src.material].set : 0);
    auto it = src.attributes.find(set);
    if (it == src.attributes.end() && set != "TEXCOORD_0") {
      warn(label + ": its material's base colour reads " + set + ", which the primitive lacks; TEXCOORD_0 used");
      set = "TEXCOORD_0";
      it = src.attributes.find(set);
    }
    if (it != src.attributes.end()) {
      auto uvs = readAttribute<2>(it->second, n, label + " " + set);
      if (!uvs) return uvs.error();
      out.texcoords = std::move(*uvs);
    }
  }
  if (auto it = src.attributes.find("TANGENT"); it != src.attributes.end()) {
    auto tangents = readAttribute<4>(it->second, n, label + " TANGENT");
    if (!tangents) return tangents.error();
    out.tangents = std::move(*tangents);
  }
  if (auto it = src.attributes.find("COLOR_0"); it != src.attributes.end())
    if (auto ok = readVertexColours(it->second, label + " COLOR_0", out); !ok) return ok.error();
  if (auto ok = readSkinAttributes(reader_, gltf_, src, label, out, model_.warnings); !ok) return fail(ok.error());
  return {};
}

Result<void> GltfModelBuilder::readVertexColours(int accessor, const std::string& what, Primitive& out) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= gltf_.accessors.size())
    return fail(what + " names accessor " + std::to_string(accessor) + ", the file has " +
                std::to_string(gltf_.accessors.size()));
  const tinygltf::Accessor& acc = gltf_.accessors[static_cast<size_t>(accessor)];
  const bool vec3 = acc.type == TINYGLTF_TYPE_VEC3, vec4 = acc.type == TINYGLTF_TYPE_VEC4;
  const bool kind = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                    (acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                        acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
  if (!(vec3 || vec4) || !kind) {
    warn(what + " is not a VEC3 or VEC4 of floats or normalized unsigned bytes or shorts (glTF 2.0, 3.7.2.1); "
         "drawn without vertex colours");
    return {};
  }
  const size_t n = out.positions.size();
  if (vec3) {
    auto rgb = readAttribute<3>(accessor, n, what);
    if (!rgb) return rgb.error();
    if (auto ok = reader_.charge(n * sizeof(glm::vec4), what); !ok) return fail(ok.error());
    out.colors.resize(n);
    for (size_t v = 0; v < n; ++v) out.colors[v] = glm::vec4((*rgb)[v], 1.0f);
  } else {
    auto rgba = readAttribute<4>(accessor, n, what);
    if (!rgba) return rgba.error();
    out.colors = std::move(*rgba);
  }
  // Linear and within [0, 1] by the spec; a float file may stray outside.
  for (glm::vec4& c : out.colors) c = glm::clamp(c, glm::vec4(0.0f), glm::vec4(1.0f));
  return {};
}

Result<void> GltfModelBuilder::readTriangles(const tinygltf::Primitive& src, int mode, const std::string& label,
                                             Primitive& out) {
  const size_t n = out.positions.size();
  std::vector<uint32_t> order;
  if (src.indices >= 0) {
    auto indices = reader_.readIndices(src.indices, label + " indices");
    if (!indices) return fail(indices.error());
    for (size_t i = 0; i < indices->size(); ++i)
      if ((*indices)[i] >= n)
        return fail(label + ": index " + std::to_string((*indices)[i]) + " at position " + std::to_string(i) +
                    " is out of range of " + std::to_string(n) + " vertices");
    order = std::move(*indices);
  } else {
    order.resize(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
  }
  if (mode == TINYGLTF_MODE_TRIANGLES && order.size() % 3 != 0)
    warn(label + " has " + std::to_string(order.size()) + " indices, not a multiple of 3; the last " +
         std::to_string(order.size() % 3) + " ignored");
  out.indices = triangulate(order, mode);
  return {};
}

void GltfModelBuilder::assignMaterial(const tinygltf::Primitive& src, const std::string& label, Primitive& out) {
  if (src.material >= 0 && static_cast<size_t>(src.material) >= model_.materials.size()) {
    warn(label + " refers to material " + std::to_string(src.material) + ", the file has " +
         std::to_string(model_.materials.size()) + "; default material used");
    out.material = -1;
  } else {
    out.material = src.material;
  }
  // KHR_texture_transform baked into this primitive's own copy of its UV set.
  if (out.material >= 0 && baseColorUvs_[out.material].transform)
    for (glm::vec2& uv : out.texcoords) uv = applyUvTransform(*baseColorUvs_[out.material].transform, uv);
}

Result<void> GltfModelBuilder::readMorphTargets(const tinygltf::Primitive& src, const std::string& label,
                                                bool generatedNormals, Primitive& out) {
  const size_t n = out.positions.size();
  // A target costs at least a dense delta per vertex where it is drawn, even
  // one that names no accessor or the same one as many others (what it reads
  // is charged by the reader on top).
  const std::string targets = label + ": " + std::to_string(src.targets.size()) + " morph targets of " +
                           std::to_string(n) + " vertices";
  if (auto ok = budget_.charge(src.targets.size(), sizeof(MorphTarget) + n * sizeof(glm::vec3), targets); !ok)
    return fail(ok.error());
  out.targets.resize(src.targets.size());
  bool warnedOther = false;
  for (size_t t = 0; t < src.targets.size(); ++t) {
    MorphTarget& target = out.targets[t];
    for (const auto& [semantic, accessor] : src.targets[t]) {
      const std::string what = label + " target " + std::to_string(t) + " " + semantic;
      if (semantic == "POSITION" || semantic == "NORMAL" || semantic == "TANGENT") {
        auto deltas = readAttribute<3>(accessor, n, what);
        if (!deltas) return deltas.error();
        (semantic == "POSITION" ? target.positions : semantic == "NORMAL" ? target.normals : target.tangents) =
            std::move(*deltas);
      } else if (!warnedOther) {
        warn(label + " morphs " + semantic + ", which is ignored (only POSITION, NORMAL, TANGENT are morphed)");
        warnedOther = true;
      }
    }
    // Normals we made up must follow the shape too: derive their deltas
    // from the fully applied target.
    if (generatedNormals && !target.positions.empty()) {
      std::vector<glm::vec3> moved(n);
      for (size_t v = 0; v < n; ++v) moved[v] = out.positions[v] + target.positions[v];
      target.normals = computeSmoothNormals(moved, out.indices);
      for (size_t v = 0; v < n; ++v) target.normals[v] -= out.normals[v];
    }
  }
  return {};
}

Result<void> GltfModelBuilder::loadMesh(int m) {
  const tinygltf::Mesh& src = gltf_.meshes[m];
  Mesh mesh;
  mesh.name = src.name;
  size_t targetCount = 0;
  bool targetCountKnown = false;
  for (size_t p = 0; p < src.primitives.size(); ++p) {
    Primitive prim;
    auto kept = loadPrimitive(m, static_cast<int>(p), prim, targetCount, targetCountKnown);
    if (!kept) return kept.error();
    if (*kept) mesh.primitives.push_back(std::move(prim));
  }
  if (!targetCountKnown) targetCount = src.weights.size();

  std::vector<std::string> names;
  if (src.extras.IsObject() && src.extras.Has("targetNames")) {
    const tinygltf::Value& list = src.extras.Get("targetNames");
    bool allStrings = list.IsArray();
    for (size_t i = 0; allStrings && i < list.ArrayLen(); ++i) {
      const tinygltf::Value& v = list.Get(static_cast<int>(i));
      if (!v.IsString()) allStrings = false;
      else names.push_back(v.Get<std::string>());
    }
    if (!allStrings || names.size() != targetCount) {
      warn(meshLabel(m) + ": extras.targetNames is not a list of " + std::to_string(targetCount) +
           " strings; names target_N used");
      names.clear();
    }
  }
  if (names.empty())
    for (size_t t = 0; t < targetCount; ++t) names.push_back("target_" + std::to_string(t));
  mesh.targetNames = std::move(names);

  mesh.defaultWeights.assign(targetCount, 0.0f);
  if (!src.weights.empty()) {
    if (src.weights.size() != targetCount) {
      warn(meshLabel(m) + " has " + std::to_string(src.weights.size()) + " default weights for " +
           std::to_string(targetCount) + " targets; zeros used");
    } else {
      for (size_t t = 0; t < targetCount; ++t) {
        const float w = static_cast<float>(src.weights[t]);
        if (!std::isfinite(w)) return fail(meshLabel(m) + ": default weight " + std::to_string(t) + " is not finite");
        mesh.defaultWeights[t] = w;
      }
    }
  }
  model_.meshes.push_back(std::move(mesh));
  return {};
}

}  // namespace eng
