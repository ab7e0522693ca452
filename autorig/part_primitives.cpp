#include "autorig/part_primitives.h"

#include <array>
#include <map>
#include <vector>

namespace autorig {
namespace {

// What a split primitive becomes: the skin (and whatever else is not an inner
// part) keeps the primitive; each eyeball, the teeth and the tongue a new one.
enum class Group : uint8_t { Rest, EyeRight, EyeLeft, Teeth, Tongue };
constexpr std::array<const char*, 5> kMaterialName = {"", "Eyeball (right)", "Eyeball (left)", "Teeth", "Tongue"};

Group groupOf(FacePart part) {
  switch (part) {
    case FacePart::EyeballRight: return Group::EyeRight;
    case FacePart::EyeballLeft: return Group::EyeLeft;
    case FacePart::UpperTeeth: case FacePart::LowerTeeth: return Group::Teeth;
    case FacePart::Tongue: return Group::Tongue;
    default: return Group::Rest;
  }
}

// The vertices `vertices` of `source` (in that order) with the triangles `indices` (source numbering).
eng::Primitive subset(const eng::Primitive& source, const std::vector<uint32_t>& vertices, const std::vector<uint32_t>& indices) {
  std::vector<uint32_t> local(source.vertexCount(), 0);
  for (uint32_t k = 0; k < vertices.size(); ++k) local[vertices[k]] = k;
  auto pick = [&](const auto& attribute, size_t perVertex = 1) {
    std::decay_t<decltype(attribute)> out;
    if (attribute.empty()) return out;
    out.reserve(vertices.size() * perVertex);
    for (uint32_t v : vertices)
      for (size_t s = 0; s < perVertex; ++s) out.push_back(attribute[v * perVertex + s]);
    return out;
  };
  eng::Primitive out;
  out.positions = pick(source.positions);
  out.normals = pick(source.normals);
  out.texcoords = pick(source.texcoords);
  out.tangents = pick(source.tangents);
  out.colors = pick(source.colors);
  out.joints = pick(source.joints, source.influenceSets());
  out.jointWeights = pick(source.jointWeights, source.influenceSets());
  out.material = source.material;
  for (const eng::MorphTarget& t : source.targets)
    out.targets.push_back(eng::MorphTarget{pick(t.positions), pick(t.normals), pick(t.tangents)});
  out.indices.reserve(indices.size());
  for (uint32_t i : indices) out.indices.push_back(local[i]);
  return out;
}

}  // namespace

size_t separateInnerParts(eng::Model& model, const PosedFace& posed, const FaceParts& parts) {
  size_t added = 0;
  std::map<std::pair<int, Group>, int> materialOf;  // (source material, group) -> the part's material
  for (size_t k = 0; k < posed.primitives.size() && k < parts.vertexParts.size(); ++k) {
    const PosedPrimitive& pp = posed.primitives[k];
    if (pp.mesh >= model.meshes.size() || pp.primitive >= model.meshes[pp.mesh].primitives.size()) continue;
    eng::Mesh& mesh = model.meshes[pp.mesh];
    const eng::Primitive& prim = mesh.primitives[pp.primitive];
    const std::vector<FacePart>& vertexParts = parts.vertexParts[k];
    if (vertexParts.size() != prim.vertexCount() || !prim.colors.empty()) continue;
    if (prim.material >= 0 && size_t(prim.material) < model.materials.size() &&
        model.materials[size_t(prim.material)].baseColorImage >= 0)
      continue;  // textured: its eyes and teeth are painted
    // Triangles by the group of their first corner (a part is whole components).
    std::array<std::vector<uint32_t>, 5> triangles;
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3)
      for (int c = 0; c < 3; ++c) triangles[size_t(groupOf(vertexParts[prim.indices[t]]))].push_back(prim.indices[t + size_t(c)]);
    size_t groups = 0;
    for (const auto& g : triangles) groups += !g.empty();
    if (groups < 2) continue;
    std::vector<eng::Primitive> pieces;
    for (size_t g = 0; g < triangles.size(); ++g) {
      if (triangles[g].empty()) continue;
      std::vector<uint32_t> vertices;
      std::vector<bool> used(prim.vertexCount(), false);
      for (uint32_t v : triangles[g])
        if (!used[v]) used[v] = true, vertices.push_back(v);
      eng::Primitive piece = subset(prim, vertices, triangles[g]);
      if (g != size_t(Group::Rest)) {
        const auto [it, isNew] = materialOf.try_emplace({prim.material, Group(g)}, int(model.materials.size()));
        if (isNew) {
          eng::Material material = prim.material >= 0 ? model.materials[size_t(prim.material)] : eng::Material{};
          material.name = kMaterialName[g];
          material.detailLayers.clear();
          model.materials.push_back(std::move(material));
        }
        piece.material = it->second;
      }
      pieces.push_back(std::move(piece));
    }
    // The rest (first, when there is one) keeps the primitive's place.
    mesh.primitives[pp.primitive] = std::move(pieces.front());
    for (size_t p = 1; p < pieces.size(); ++p) mesh.primitives.push_back(std::move(pieces[p]));
    added += pieces.size() - 1;
  }
  return added;
}

}  // namespace autorig
