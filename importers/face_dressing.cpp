#include "importers/face_dressing.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/uv_raster.h"
#include "engine/scene/inner_face_parts.h"
#include "importers/painted_brows.h"
#include "importers/procedural_eyes.h"
#include "importers/vertex_occlusion.h"

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

// The material's textures besides its base colour dropped; its emission goes
// with its emissive texture (alone, the factor would light the whole surface).
void dropOtherTextures(Material& m) {
  if (m.emissiveImage >= 0) m.emissiveFactor = glm::vec3(0.0f);
  for (const MaterialTexture& slot : kMaterialTextures) m.*slot.image = -1;
}

enum class Part { None, Teeth, Tongue, Skin };

// Linear albedos: ivory teeth (a shade below white, so they do not glow in a
// shadowed mouth), a muted tongue, and a mid skin tone with headroom both
// ways for the key's highlights and the creases' shadows.
constexpr glm::vec3 kTeethColour{0.62f, 0.58f, 0.50f};
constexpr glm::vec3 kTongueColour{0.42f, 0.13f, 0.12f};
constexpr glm::vec3 kSkinColour{0.60f, 0.42f, 0.34f};

struct PlannedPrimitive {
  size_t mesh, primitive;
  Part part;
};

std::vector<PlannedPrimitive> plan(const Model& model) {
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  // Skin only on a model that is a face: it has eyeballs, or a mesh or node
  // says head or face. A morphing sphere or cube sample stays as authored.
  const std::vector<EyePrimitive> eyes = findUntexturedEyes(model);
  bool isFace = !eyes.empty();
  for (size_t m = 0; m < model.meshes.size() && !isFace; ++m) {
    const std::vector<std::string_view> names = meshAndNodeNames(model, m, nodeOfMesh[m]);
    isFace = anyNameContains(names, "head") || anyNameContains(names, "face");
  }
  std::vector<PlannedPrimitive> planned;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    const std::vector<std::string_view> names = meshAndNodeNames(model, m, nodeOfMesh[m]);
    const bool eyeNamed = std::any_of(names.begin(), names.end(),
                                      [](std::string_view n) { return namesAnEyeball(std::string(n)); });
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      if (!unauthoredPlain(model, prim)) continue;
      // The mesh's and nodes' names, and the material's (a scan's merged
      // mouth given its own primitive by the rig: autorig/part_primitives.h).
      std::vector<std::string_view> partNames = names;
      if (prim.material >= 0 && size_t(prim.material) < model.materials.size()) partNames.push_back(model.materials[size_t(prim.material)].name);
      Part part = Part::None;
      if (anyNameContains(partNames, "teeth") || anyNameContains(partNames, "tooth"))
        part = Part::Teeth;
      else if (anyNameContains(partNames, "tongue"))
        part = Part::Tongue;
      else if (isFace && !eyeNamed && !materialNamesAnEyeball(model, prim.material) && !mesh.targetNames.empty() &&
               std::none_of(eyes.begin(), eyes.end(), [&](const EyePrimitive& e) {
                 return size_t(e.mesh) == m && size_t(e.primitive) == p;
               }))
        part = Part::Skin;
      if (part != Part::None) planned.push_back({m, p, part});
    }
  }
  return planned;
}

// Brows on the dressed skin (painted_brows.h): into a texture through the
// skin's UVs, one per dressed skin material, or into the vertex colours of a
// primitive without UVs (coarser, but still a brow).
void paintBrows(Model& model, const std::vector<PlannedPrimitive>& planned, const std::vector<EyePrimitive>& eyes) {
  constexpr int kTextureSize = 1024;
  constexpr float kOpacity = 0.8f;
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  std::map<int, PaintImage> textures;  // dressed skin material -> its texture
  std::vector<Primitive*> withoutUvs;   // painted through their vertex colours
  // The painted texture replaces whatever the skin's UVs were made for: they
  // are fitted into it per material, the primitives sharing it together (a
  // face whose lips are a primitive of their own keeps them beside the rest).
  std::map<int, std::vector<std::vector<glm::vec2>*>> uvsOfMaterial;
  for (const PlannedPrimitive& p : planned)
    if (Primitive& prim = model.meshes[p.mesh].primitives[p.primitive];
        p.part == Part::Skin && prim.texcoords.size() == prim.positions.size() &&
        !browFrames(model, eyes, nodeOfMesh[p.mesh]).empty())
      uvsOfMaterial[prim.material].push_back(&prim.texcoords);
  for (auto& [material, uvs] : uvsOfMaterial) fitIntoUnitSquare(uvs);
  for (const PlannedPrimitive& p : planned) {
    if (p.part != Part::Skin) continue;
    Primitive& prim = model.meshes[p.mesh].primitives[p.primitive];
    const std::vector<BrowFrame> frames = browFrames(model, eyes, nodeOfMesh[p.mesh]);
    if (frames.empty()) continue;
    const size_t n = prim.positions.size();
    if (prim.texcoords.size() == n) {
      PaintImage& image = textures.try_emplace(prim.material, kTextureSize, kTextureSize).first->second;
      rasterizeUv(kTextureSize, kTextureSize, prim.texcoords, prim.indices,
                  [&](int x, int y, uint32_t triangle, const glm::vec3& b) {
                    const uint32_t* tri = &prim.indices[size_t(triangle) * 3];
                    const glm::vec3 at = prim.positions[tri[0]] * b.x + prim.positions[tri[1]] * b.y +
                                         prim.positions[tri[2]] * b.z;
                    const float c = kOpacity * browCoverage(frames, at);
                    image.set(x, y, glm::vec4(glm::mix(kSkinColour, browColour(), c), 1.0f));
                  });
    } else {
      withoutUvs.push_back(&prim);
      prim.colors.resize(n, glm::vec4(1.0f));
      for (size_t v = 0; v < n; ++v) {
        const float c = kOpacity * browCoverage(frames, prim.positions[v]);
        prim.colors[v] *= glm::vec4(glm::mix(glm::vec3(1.0f), browColour() / kSkinColour, c), 1.0f);
      }
    }
  }
  for (auto& [material, image] : textures) {
    image.dilate(4);
    Image painted;
    painted.name = "painted brows";
    painted.width = image.width;
    painted.height = image.height;
    painted.rgba8 = image.toSrgba8();
    Material& m = model.materials[size_t(material)];
    m.baseColorImage = int(model.images.size());
    m.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, m.baseColorFactor.a);
    dropOtherTextures(m);  // made for the UVs the painting replaced
    model.images.push_back(std::move(painted));
  }
  // A primitive without UVs would sample one texel of a texture made for its
  // neighbours' UVs: it keeps a copy of the material with the plain skin tone.
  std::map<int, int> untextured;  // textured skin material -> its untextured copy
  for (Primitive* prim : withoutUvs) {
    if (!textures.contains(prim->material)) continue;
    auto [it, added] = untextured.try_emplace(prim->material, int(model.materials.size()));
    if (added) {
      Material plain = model.materials[size_t(prim->material)];
      plain.baseColorImage = -1;
      dropOtherTextures(plain);
      plain.baseColorFactor = glm::vec4(kSkinColour, plain.baseColorFactor.a);
      model.materials.push_back(std::move(plain));
    }
    prim->material = it->second;
  }
}

}  // namespace

FaceDressing planFaceDressing(const Model& model) {
  FaceDressing d;
  d.eyes = findUntexturedEyes(model).size();
  for (const PlannedPrimitive& p : plan(model)) (p.part == Part::Skin ? d.skin : d.mouth) += 1;
  return d;
}

std::optional<Model> dressedForDisplay(const Model& model) {
  if (planFaceDressing(model).total() == 0) return std::nullopt;
  std::optional<Model> dressed = model;
  dressUntexturedFace(*dressed);
  return dressed;
}

FaceDressing dressUntexturedFace(Model& model) {
  // Planned before the eyes add their material, so an eye never counts as skin.
  const std::vector<PlannedPrimitive> planned = plan(model);
  const std::vector<EyePrimitive> eyes = findUntexturedEyes(model);
  if (planned.empty() && eyes.empty()) return {};
  // Baked on the undressed model (the geometry is the same): dark in the
  // mouth bag, nostrils and around the eyeballs; never quite black.
  const auto occlusion = bakeVertexOcclusion(model);
  // floor: the darkest a fully hidden vertex gets. Teeth are hidden behind
  // closed lips at rest but must stay teeth when the lips part.
  auto shade = [&](size_t mesh, size_t primitive, float floor) {
    Primitive& prim = model.meshes[mesh].primitives[primitive];
    const std::vector<float>& visible = occlusion[mesh][primitive];
    prim.colors.resize(prim.positions.size(), glm::vec4(1.0f));
    for (size_t v = 0; v < prim.positions.size() && v < visible.size(); ++v) {
      const float t = std::clamp((visible[v] - 0.05f) / 0.8f, 0.0f, 1.0f);
      const float light = floor + (1.0f - floor) * t * t * (3.0f - 2.0f * t);
      prim.colors[v] = glm::vec4(glm::vec3(prim.colors[v]) * light, prim.colors[v].a);
    }
  };
  FaceDressing d;
  // The eyes first: shaded, they would count as painted per vertex.
  d.eyes = dressUntexturedEyes(model);
  for (const PlannedPrimitive& p : planned) shade(p.mesh, p.primitive, p.part == Part::Teeth ? 0.55f : 0.12f);
  for (const EyePrimitive& e : eyes) shade(size_t(e.mesh), size_t(e.primitive), 0.25f);
  std::map<std::pair<int, Part>, int> dressedMaterial;  // (source material, part) -> new material
  for (const PlannedPrimitive& p : planned) {
    Primitive& prim = model.meshes[p.mesh].primitives[p.primitive];
    auto [it, added] = dressedMaterial.try_emplace({prim.material, p.part}, int(model.materials.size()));
    if (added) {
      Material material = prim.material >= 0 ? model.materials[size_t(prim.material)] : Material{};
      const glm::vec3 colour = p.part == Part::Teeth ? kTeethColour : p.part == Part::Tongue ? kTongueColour : kSkinColour;
      material.baseColorFactor = glm::vec4(colour, material.baseColorFactor.a);
      material.name += p.part == Part::Teeth ? " (teeth)" : p.part == Part::Tongue ? " (tongue)" : " (skin tone)";
      model.materials.push_back(std::move(material));
    }
    prim.material = it->second;
    (p.part == Part::Skin ? d.skin : d.mouth) += 1;
  }
  paintBrows(model, planned, eyes);
  return d;
}

}  // namespace importers
