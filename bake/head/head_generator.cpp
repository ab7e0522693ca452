#include "bake/head/head_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/common.hpp>

#include "bake/head/ear.h"
#include "bake/head/eye_opening.h"
#include "bake/head/eyeball.h"
#include "bake/head/head_proportions.h"
#include "bake/head/head_sdf.h"
#include "bake/head/mouth_interior.h"
#include "bake/head/skin_painter.h"
#include "bake/head/skin_surface.h"
#include "bake/head/surface_normals.h"
#include "bake/head/teeth.h"
#include "bake/head/tongue.h"
#include "engine/core/uv_raster.h"
#include "facial/runtime/rig/action_units.h"

namespace bake {
namespace {

using glm::vec3;

// Normal deltas below this are dropped (keeps targets sparse; invisible).
constexpr float kNegligibleNormal = 8e-3f;

// One primitive of the "Head" mesh under construction: its vertices are a
// contiguous range of the deformable point set.
struct HeadPrimitiveData {
  std::vector<vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> weldIds;  // local
  size_t offset = 0;              // first vertex in DeformableHead
};

HeadPrimitiveData fromPart(const PartMesh& m) {
  HeadPrimitiveData p;
  p.positions = m.positions;
  p.normals = m.normals;
  p.uvs = m.uvs;
  p.indices = m.indices;
  p.weldIds = m.weldIds;
  return p;
}

// Ray along -Z from in front of the face onto the skin: the front-most hit.
std::optional<vec3> snapToSkin(const glm::vec2& xy, const SkinSurface& s) {
  std::optional<vec3> best;
  for (size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    const uint32_t i0 = s.indices[t], i1 = s.indices[t + 1], i2 = s.indices[t + 2];
    if (s.parts[i0] != SkinPart::Skin) continue;
    const vec3 &a = s.positions[i0], &b = s.positions[i1], &c = s.positions[i2];
    const float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (area <= 1e-14f) continue;  // back-facing or edge-on seen from +Z
    const float w0 = ((b.x - xy.x) * (c.y - xy.y) - (c.x - xy.x) * (b.y - xy.y)) / area;
    const float w1 = ((c.x - xy.x) * (a.y - xy.y) - (a.x - xy.x) * (c.y - xy.y)) / area;
    const float w2 = 1.0f - w0 - w1;
    constexpr float kEdge = -1e-5f;  // points on a shared edge belong to both triangles
    if (w0 < kEdge || w1 < kEdge || w2 < kEdge) continue;
    const vec3 hit = a * w0 + b * w1 + c * w2;
    if (!best || hit.z > best->z) best = hit;
  }
  return best;
}

std::string describeXy(const glm::vec2& xy) {
  return "(" + std::to_string(xy.x) + ", " + std::to_string(xy.y) + ")";
}

// The deformable "Head" mesh under construction (skin, mouth pocket, teeth,
// tongue, in HeadPrimitive order) and the point set the action units deform.
struct HeadAssembly {
  std::vector<HeadPrimitiveData> prims;
  std::vector<int> skinLocal;  // SkinSurface vertex -> index in its primitive
  DeformableHead head;
};

// Skin vertices go to the skin primitive, the rest of the surface (the mouth
// pocket) to the mouth primitive.
int primitiveOfSkinVertex(const SkinSurface& skin, size_t v) { return skin.parts[v] == SkinPart::Skin ? 0 : 1; }

HeadAssembly assembleHead(const SkinSurface& skin, const std::vector<vec3>& skinNormals, const EyeOpening& eyeL,
                          const EyeOpening& eyeR, const PartMesh& teethUpper, const PartMesh& teethLower,
                          const PartMesh& tongue) {
  HeadAssembly a;
  std::vector<HeadPrimitiveData>& prims = a.prims;
  prims.resize(5);
  a.skinLocal.assign(skin.vertexCount(), -1);
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    HeadPrimitiveData& p = prims[primitiveOfSkinVertex(skin, v)];
    a.skinLocal[v] = static_cast<int>(p.positions.size());
    p.positions.push_back(skin.positions[v]);
    p.normals.push_back(skinNormals[v]);
    p.uvs.push_back(skin.uvs[v]);
  }
  for (size_t v = 0; v < skin.vertexCount(); ++v)
    prims[primitiveOfSkinVertex(skin, v)].weldIds.push_back(0);  // unused for these two
  for (size_t t = 0; t < skin.indices.size(); ++t)
    prims[primitiveOfSkinVertex(skin, skin.indices[t - t % 3])].indices.push_back(
        static_cast<uint32_t>(a.skinLocal[skin.indices[t]]));
  prims[2] = fromPart(teethUpper);
  prims[3] = fromPart(teethLower);
  prims[4] = fromPart(tongue);

  DeformableHead& head = a.head;
  head.eyes = {{eyeL.centre(), eyeL.radius()}, {eyeR.centre(), eyeR.radius()}};
  const HeadPart partOf[5] = {HeadPart::Skin, HeadPart::Mouth, HeadPart::TeethUpper, HeadPart::TeethLower,
                              HeadPart::Tongue};
  std::vector<std::vector<float>> jawOf(5);
  jawOf[0].resize(prims[0].positions.size());
  jawOf[1].resize(prims[1].positions.size());
  for (size_t v = 0; v < skin.vertexCount(); ++v) jawOf[primitiveOfSkinVertex(skin, v)][a.skinLocal[v]] = skin.jawSide[v];
  jawOf[2].assign(prims[2].positions.size(), 0.0f);
  jawOf[3].assign(prims[3].positions.size(), 1.0f);
  jawOf[4].assign(prims[4].positions.size(), 1.0f);
  for (int p = 0; p < 5; ++p) {
    prims[p].offset = head.positions.size();
    for (size_t v = 0; v < prims[p].positions.size(); ++v) {
      const vec3& pos = prims[p].positions[v];
      head.positions.push_back(pos);
      head.parts.push_back(partOf[p]);
      head.jawSide.push_back(jawOf[p][v]);
      // Skin near an eyeball slides over it when a lid moves.
      int8_t eye = -1;
      float slide = 0.0f;
      if (p == 0) {
        for (int e = 0; e < 2; ++e) {
          const float rho = glm::length(pos - head.eyes[e].centre);
          const float w = 1.0f - glm::smoothstep(head.eyes[e].radius + 0.0018f, head.eyes[e].radius + 0.0045f, rho);
          if (w > slide) {
            slide = w;
            eye = static_cast<int8_t>(e);
          }
        }
      }
      head.lidEye.push_back(eye);
      head.lidSlide.push_back(slide);
    }
  }
  return a;
}

// Each landmark of the spec resolved to a point on (or in) the generated head.
eng::Result<LandmarkPoints> resolveLandmarks(const HeadRigSpec& spec, const SkinSurface& skin,
                                             const std::map<std::string, vec3>& features, const DeformableHead& head) {
  LandmarkPoints lm;
  for (const LandmarkDef& d : spec.landmarks) {
    vec3 p(0.0f);
    switch (d.kind) {
      case LandmarkDef::Kind::Surface: {
        const std::optional<vec3> hit = snapToSkin(d.xy, skin);
        if (!hit)
          return eng::makeError(eng::ErrorKind::Malformed, spec.source + ": landmark \"" + d.name + "\" at xy " + describeXy(d.xy) +
                                ": no skin under this point");
        p = *hit;
        break;
      }
      case LandmarkDef::Kind::Feature: {
        auto it = features.find(d.feature);
        if (it == features.end()) {
          std::string known;
          for (const auto& [name, unused] : features) known += (known.empty() ? "" : ", ") + name;
          return eng::makeError(eng::ErrorKind::Malformed, spec.source + ": landmark \"" + d.name + "\": unknown feature \"" + d.feature +
                                "\" (known: " + known + ")");
        }
        p = it->second;
        break;
      }
      case LandmarkDef::Kind::Position:
        p = d.position;
        break;
    }
    p += d.offset;
    // Jaw side of the nearest deformable vertex decides which masks cover it.
    size_t nearest = 0;
    float best = std::numeric_limits<float>::max();
    for (size_t v = 0; v < head.positions.size(); ++v) {
      const float dist = glm::length(head.positions[v] - p);
      if (dist < best) {
        best = dist;
        nearest = v;
      }
    }
    lm.names.push_back(d.name);
    lm.positions.push_back(p);
    lm.jawSide.push_back(head.jawSide[nearest]);
  }
  for (size_t a = 0; a < lm.names.size(); ++a)
    for (size_t b = a + 1; b < lm.names.size(); ++b)
      if (glm::length(lm.positions[a] - lm.positions[b]) < 5e-4f)
        return eng::makeError(eng::ErrorKind::Malformed, spec.source + ": landmarks \"" + lm.names[a] + "\" and \"" + lm.names[b] +
                              "\" resolve to points closer than 0.5 mm");
  return lm;
}

// Normals of each primitive deformed by one action unit's deltas, each over
// its own topology (the skin and mouth pocket share one welded surface).
std::vector<std::vector<vec3>> deformedNormals(const SkinSurface& skin, const HeadAssembly& a,
                                               const std::vector<vec3>& deltas) {
  const std::vector<HeadPrimitiveData>& prims = a.prims;
  std::vector<vec3> skinMoved(skin.vertexCount());
  for (size_t v = 0; v < skin.vertexCount(); ++v)
    skinMoved[v] = skin.positions[v] + deltas[prims[primitiveOfSkinVertex(skin, v)].offset + a.skinLocal[v]];
  const std::vector<vec3> skinMovedNormals = weldedNormals(skinMoved, skin.indices, skin.weldIds);
  std::vector<std::vector<vec3>> movedNormals(5);
  movedNormals[0].resize(prims[0].positions.size());
  movedNormals[1].resize(prims[1].positions.size());
  for (size_t v = 0; v < skin.vertexCount(); ++v)
    movedNormals[primitiveOfSkinVertex(skin, v)][a.skinLocal[v]] = skinMovedNormals[v];
  for (int p = 2; p < 5; ++p) {
    std::vector<vec3> moved(prims[p].positions.size());
    for (size_t v = 0; v < moved.size(); ++v) moved[v] = prims[p].positions[v] + deltas[prims[p].offset + v];
    movedNormals[p] = weldedNormals(moved, prims[p].indices, prims[p].weldIds);
  }
  return movedNormals;
}

// Mesh "Head" with one morph target per action unit, in canonical order.
eng::Result<eng::Mesh> bakeHeadMesh(const HeadRigSpec& spec, const LandmarkPoints& lm, const SkinSurface& skin,
                                    const HeadAssembly& a) {
  const std::vector<HeadPrimitiveData>& prims = a.prims;
  eng::Mesh headMesh;
  headMesh.name = "Head";
  for (int p = 0; p < 5; ++p) {
    eng::Primitive prim;
    prim.positions = prims[p].positions;
    prim.normals = prims[p].normals;
    prim.texcoords = prims[p].uvs;
    prim.indices = prims[p].indices;
    headMesh.primitives.push_back(std::move(prim));
  }
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) {
    const ActionUnitDef* def = nullptr;
    for (const ActionUnitDef& d : spec.actionUnits)
      if (d.name == info.name) def = &d;
    if (!def) return eng::makeError(eng::ErrorKind::Malformed, spec.source + ": action unit \"" + std::string(info.name) + "\" is missing");
    eng::Result<std::vector<vec3>> deltas = bakeActionUnit(*def, spec, lm, a.head);
    if (!deltas) return deltas.error();
    headMesh.targetNames.emplace_back(info.name);
    headMesh.defaultWeights.push_back(0.0f);
    const std::vector<std::vector<vec3>> movedNormals = deformedNormals(skin, a, *deltas);
    for (int p = 0; p < 5; ++p) {
      eng::MorphTarget target;
      const size_t count = prims[p].positions.size();
      target.positions.resize(count);
      target.normals.resize(count);
      for (size_t v = 0; v < count; ++v) {
        target.positions[v] = (*deltas)[prims[p].offset + v];
        vec3 dn = movedNormals[p][v] - prims[p].normals[v];
        if (glm::length(dn) < kNegligibleNormal) dn = vec3(0.0f);
        target.normals[v] = dn;
      }
      headMesh.primitives[p].targets.push_back(std::move(target));
    }
  }
  return headMesh;
}

// Painted images and the materials that use them, in the order the meshes
// index them: skin, eye, teeth, mouth interior, tongue, ear.
void paintMaterials(eng::Model& model, const HeadRigSpec& spec, const HeadProportions& prop, const HeadSdf& sdf,
                    const SkinSurface& skin, const std::vector<vec3>& skinNormals, const HeadOptions& options) {
  std::vector<float> occlusion(skin.vertexCount(), 1.0f);
  for (size_t v = 0; v < skin.vertexCount(); ++v) occlusion[v] = sdf.occlusion(skin.positions[v], skinNormals[v]);
  const SkinPainter painter(prop, sdf);
  SkinImages skinImages = paintSkin(skin, skinNormals, occlusion, painter, options.skinTextureSize, options.detailTextureSize);
  model.images.push_back(std::move(skinImages.baseColour));
  const int firstDetail = static_cast<int>(model.images.size());
  for (eng::Image& img : skinImages.details) model.images.push_back(std::move(img));
  const int eyeImage = static_cast<int>(model.images.size());
  model.images.push_back(paintEyeTexture(prop, options.eyeTextureWidth, options.eyeTextureWidth / 2));
  const int teethImage = static_cast<int>(model.images.size());
  model.images.push_back(paintTeethTexture(256, 64));
  const int mouthImage = static_cast<int>(model.images.size());
  model.images.push_back(paintMouthInteriorTexture(64));

  eng::Material skinMaterial;
  skinMaterial.name = "Skin";
  skinMaterial.baseColorImage = 0;
  skinMaterial.roughness = 0.55f;
  for (const DetailLayerDef& d : spec.detailLayers) {
    const auto& names = skinDetailLayerNames();
    const int layer = static_cast<int>(std::find(names.begin(), names.end(), d.layer) - names.begin());
    skinMaterial.detailLayers.push_back({firstDetail + layer, d.target, d.strength});
  }
  eng::Material eyeMaterial;
  eyeMaterial.name = "Eye";
  eyeMaterial.baseColorImage = eyeImage;
  eyeMaterial.roughness = 0.12f;
  eng::Material teethMaterial;
  teethMaterial.name = "Teeth";
  teethMaterial.baseColorImage = teethImage;
  teethMaterial.roughness = 0.3f;
  eng::Material mouthMaterial;
  mouthMaterial.name = "MouthInterior";
  mouthMaterial.baseColorImage = mouthImage;
  mouthMaterial.roughness = 0.45f;
  mouthMaterial.doubleSided = true;
  eng::Material tongueMaterial;
  tongueMaterial.name = "Tongue";
  // Darker than the lips: the tongue sits in the mouth's shade, and a bright
  // tongue made an open mouth read as a pink blob rather than an opening.
  tongueMaterial.baseColorFactor = glm::vec4(eng::srgb(128, 54, 58), 1.0f);
  tongueMaterial.roughness = 0.4f;
  eng::Material earMaterial;
  earMaterial.name = "Ear";
  earMaterial.baseColorFactor = glm::vec4(eng::srgb(232, 176, 150), 1.0f);
  earMaterial.roughness = 0.55f;
  model.materials = {skinMaterial, eyeMaterial, teethMaterial, mouthMaterial, tongueMaterial, earMaterial};
}

eng::Primitive primitiveOf(const PartMesh& m, int material) {
  eng::Primitive prim;
  prim.positions = m.positions;
  prim.normals = m.normals;
  prim.texcoords = m.uvs;
  prim.indices = m.indices;
  prim.material = material;
  return prim;
}

// Meshes Head, EyeLeft, EyeRight (no targets) and Ears (no targets), each on
// its own node under the root node "BuiltInHead". Each eyeball's node sits at
// the ball's centre with the mesh around its origin: the node is the eye's
// joint, so a gaze turns the ball in its socket (app/skeleton_motion.h finds
// it by name), as eye joints do on the avatars users bring.
void addMeshesAndNodes(eng::Model& model, eng::Mesh headMesh, const EyeOpening& eyeL, const EyeOpening& eyeR,
                       const HeadProportions& prop) {
  const int materialOf[5] = {0, 3, 2, 2, 4};
  for (int p = 0; p < 5; ++p) headMesh.primitives[p].material = materialOf[p];
  auto eyeMesh = [&](const EyeOpening& eye, const char* name) {
    eng::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(primitiveOf(buildEyeball(eye, prop), 1));
    for (vec3& p : mesh.primitives[0].positions) p -= eye.centre();
    return mesh;
  };
  eng::Mesh ears;
  ears.name = "Ears";
  ears.primitives.push_back(primitiveOf(buildEar(1.0f), 5));
  ears.primitives.push_back(primitiveOf(buildEar(-1.0f), 5));
  // Ears have no texture coordinates worth keeping (flat colour material).
  for (eng::Primitive& prim : ears.primitives) prim.texcoords.clear();
  model.meshes = {std::move(headMesh), eyeMesh(eyeL, "EyeLeft"), eyeMesh(eyeR, "EyeRight"), std::move(ears)};

  eng::Node root;
  root.name = "BuiltInHead";
  root.children = {1, 2, 3, 4};
  model.nodes.push_back(root);
  const char* nodeNames[4] = {"Head", "EyeLeft", "EyeRight", "Ears"};
  const vec3 nodeAt[4] = {vec3(0.0f), eyeL.centre(), eyeR.centre(), vec3(0.0f)};
  for (int m = 0; m < 4; ++m) {
    eng::Node n;
    n.name = nodeNames[m];
    n.parent = 0;
    n.mesh = m;
    n.translation = nodeAt[m];
    model.nodes.push_back(n);
  }
  model.roots = {0};
}

}  // namespace

eng::Result<GeneratedHead> generateHead(const HeadRigSpec& spec, const HeadOptions& options) {
  const HeadProportions prop;
  const HeadSdf sdf(prop);
  eng::Result<SkinSurface> built = buildSkinSurface(prop, sdf);
  if (!built) return built.error();
  const SkinSurface& skin = *built;
  const std::vector<vec3> skinNormals = weldedNormals(skin.positions, skin.indices, skin.weldIds);

  const EyeOpening eyeL(prop, 1.0f), eyeR(prop, -1.0f);
  const vec3 seam = skin.features.at("mouth.seam_centre");
  const ToothRowShape upperRow = upperToothRow(seam), lowerRow = lowerToothRow(seam);
  std::map<std::string, vec3> features = skin.features;
  features["teeth.upper_incisor"] = vec3(0.0f, upperRow.edgeY, upperRow.frontZ);
  features["teeth.lower_incisor"] = vec3(0.0f, lowerRow.edgeY, lowerRow.frontZ);
  features["tongue.tip"] = vec3(0.0f, seam.y - 0.0075f, seam.z - 0.0136f);
  const HeadAssembly assembly = assembleHead(skin, skinNormals, eyeL, eyeR, buildToothRow(upperRow),
                                             buildToothRow(lowerRow), buildTongue(seam));

  GeneratedHead out;
  eng::Result<LandmarkPoints> landmarks = resolveLandmarks(spec, skin, features, assembly.head);
  if (!landmarks) return landmarks.error();
  out.landmarks = std::move(*landmarks);
  eng::Result<eng::Mesh> headMesh = bakeHeadMesh(spec, out.landmarks, skin, assembly);
  if (!headMesh) return headMesh.error();
  paintMaterials(out.model, spec, prop, sdf, skin, skinNormals, options);
  addMeshesAndNodes(out.model, std::move(*headMesh), eyeL, eyeR, prop);
  out.model.sourcePath = "generated:built-in-head";
  return out;
}

}  // namespace bake
