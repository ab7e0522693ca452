#include "autorig/carried_pieces.h"

#include <unordered_map>

namespace autorig {

std::string meshLabel(const eng::Model& model, size_t mesh) {
  const std::string& name = model.meshes[mesh].name;
  return name.empty() ? "mesh " + std::to_string(mesh) : name;
}

uint32_t appendVertexOf(eng::Primitive& to, const eng::Primitive& from, uint32_t v) {
  const size_t n = from.vertexCount();
  const size_t sets = from.influenceSets();
  const bool fresh = to.vertexCount() == 0;
  auto copy = [&](auto& into, const auto& values) {
    if (values.size() != n || (!fresh && into.size() != to.vertexCount())) return;
    const auto value = values[v];  // `into` may be `values`: read before it grows
    into.push_back(value);
  };
  copy(to.normals, from.normals);
  copy(to.texcoords, from.texcoords);
  copy(to.tangents, from.tangents);
  copy(to.colors, from.colors);
  for (size_t s = 0; s < sets; ++s) {
    const glm::u16vec4 joints = from.joints[v * sets + s];
    const glm::vec4 weights = from.jointWeights[v * sets + s];
    to.joints.push_back(joints);
    to.jointWeights.push_back(weights);
  }
  if (fresh) to.targets.resize(from.targets.size());
  for (size_t t = 0; t < from.targets.size() && t < to.targets.size(); ++t) {
    const eng::MorphTarget& source = from.targets[t];
    eng::MorphTarget& target = to.targets[t];
    const size_t before = to.vertexCount();
    auto copyDelta = [&](auto& into, const auto& values) {
      if (values.size() != n || (!fresh && into.size() != before)) return;
      const auto value = values[v];
      into.push_back(value);
    };
    copyDelta(target.positions, source.positions);
    copyDelta(target.normals, source.normals);
    copyDelta(target.tangents, source.tangents);
  }
  const glm::vec3 position = from.positions[v];
  to.positions.push_back(position);  // last: the counts above read the size before
  return uint32_t(to.positions.size() - 1);
}

eng::Primitive withTriangles(const eng::Primitive& prim, std::span<const uint32_t> triangles,
                             std::vector<uint32_t>* vertexOf) {
  eng::Primitive out;
  out.material = prim.material;
  std::unordered_map<uint32_t, uint32_t> index;
  for (uint32_t t : triangles)
    for (size_t c = 0; c < 3; ++c) {
      const uint32_t v = prim.indices[size_t(t) * 3 + c];
      auto [it, fresh] = index.try_emplace(v, 0u);
      if (fresh) {
        it->second = appendVertexOf(out, prim, v);
        if (vertexOf) vertexOf->push_back(v);
      }
      out.indices.push_back(it->second);
    }
  return out;
}

CarriedPieces::CarriedPieces(eng::Model& face, const PosedPrimitive& host, uint32_t anchor)
    : face_(face), host_(host), anchor_(anchor) {
  const eng::Primitive& prim = face.meshes[host.mesh].primitives[host.primitive];
  const size_t sets = prim.influenceSets();
  anchorJoints_.assign(prim.joints.begin() + ptrdiff_t(anchor * sets), prim.joints.begin() + ptrdiff_t((anchor + 1) * sets));
  anchorWeights_.assign(prim.jointWeights.begin() + ptrdiff_t(anchor * sets),
                        prim.jointWeights.begin() + ptrdiff_t((anchor + 1) * sets));
}

size_t CarriedPieces::add(const SourceFace& source, size_t piece, std::span<const glm::vec3> world, const glm::mat3& turn) {
  eng::Mesh& mesh = face_.meshes[host_.mesh];
  const glm::mat3 toLocal = host_.worldToLocal[anchor_];
  const glm::vec3 anchorLocal = mesh.primitives[host_.primitive].positions[anchor_];
  const PosedPrimitive& sp = source.posed.primitives[piece];
  const eng::Primitive& from = source.model->meshes[sp.mesh].primitives[sp.primitive];
  eng::Primitive to;
  to.indices = from.indices;
  to.texcoords = from.texcoords;
  for (size_t v = 0; v < world.size(); ++v) {
    to.positions.push_back(anchorLocal + toLocal * (world[v] - host_.positions[anchor_]));
    const glm::vec3 n = v < from.normals.size() ? toLocal * turn * glm::inverse(sp.worldToLocal[v]) * from.normals[v]
                                                : glm::vec3(0, 0, 1);
    to.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1));
    to.joints.insert(to.joints.end(), anchorJoints_.begin(), anchorJoints_.end());
    to.jointWeights.insert(to.jointWeights.end(), anchorWeights_.begin(), anchorWeights_.end());
  }
  to.targets.resize(mesh.targetNames.size());  // empty: the face's own targets leave it
  if (from.material >= 0) {
    auto [it, fresh] = materialOf_.try_emplace(from.material, int(face_.materials.size()));
    if (fresh) {
      eng::Material material = source.model->materials[size_t(from.material)];
      material.detailLayers.clear();
      // A carried piece is seen from the front only, through the face's
      // openings. Double-sided (the head's mouth is: its back is the dark inside
      // of the head), the back of a carried mouth showed where a scan's lips,
      // pulled wide at a smile, pass its corners: black spikes past the lips.
      material.doubleSided = false;
      std::vector<int*> images{&material.baseColorImage};
      for (const eng::MaterialTexture& slot : eng::kMaterialTextures) images.push_back(&(material.*slot.image));
      for (int* image : images) {
        if (*image < 0) continue;
        auto [copy, newImage] = imageOf_.try_emplace(*image, int(face_.images.size()));
        if (newImage) face_.images.push_back(source.model->images[size_t(*image)]);
        *image = copy->second;
      }
      face_.materials.push_back(std::move(material));
    }
    to.material = it->second;
  }
  const size_t added = to.vertexCount();
  mesh.primitives.push_back(std::move(to));
  return added;
}

}  // namespace autorig
