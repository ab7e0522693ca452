#include "bake/head/head_generator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

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

namespace facial {
namespace {

using glm::vec3;

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

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

}  // namespace

eng::Result<GeneratedHead> generateHead(const HeadRigSpec& spec, const HeadOptions& options) {
  const HeadProportions prop;
  const HeadSdf sdf(prop);
  eng::Result<SkinSurface> built = buildSkinSurface(prop, sdf);
  if (!built) return built.error();
  SkinSurface& skin = *built;
  const std::vector<vec3> skinNormals = weldedNormals(skin.positions, skin.indices, skin.weldIds);

  const EyeOpening eyeL(prop, 1.0f), eyeR(prop, -1.0f);
  const vec3 seam = skin.features.at("mouth.seam_centre");
  const ToothRowShape upperRow = upperToothRow(seam), lowerRow = lowerToothRow(seam);
  const PartMesh teethUpper = buildToothRow(upperRow), teethLower = buildToothRow(lowerRow);
  const PartMesh tongue = buildTongue(seam);
  std::map<std::string, vec3> features = skin.features;
  features["teeth.upper_incisor"] = vec3(0.0f, upperRow.edgeY, upperRow.frontZ);
  features["teeth.lower_incisor"] = vec3(0.0f, lowerRow.edgeY, lowerRow.frontZ);
  features["tongue.tip"] = vec3(0.0f, seam.y - 0.0075f, seam.z - 0.0136f);

  // --- the deformable "Head" mesh: skin, mouth pocket, teeth, tongue ---------
  std::vector<HeadPrimitiveData> prims(5);
  std::vector<int> skinLocal(skin.vertexCount(), -1);  // SkinSurface vertex -> index in its primitive
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    HeadPrimitiveData& p = prims[skin.parts[v] == SkinPart::Skin ? 0 : 1];
    skinLocal[v] = static_cast<int>(p.positions.size());
    p.positions.push_back(skin.positions[v]);
    p.normals.push_back(skinNormals[v]);
    p.uvs.push_back(skin.uvs[v]);
  }
  for (size_t v = 0; v < skin.vertexCount(); ++v)
    prims[skin.parts[v] == SkinPart::Skin ? 0 : 1].weldIds.push_back(0);  // unused for these two
  for (size_t t = 0; t < skin.indices.size(); ++t)
    prims[skin.parts[skin.indices[t - t % 3]] == SkinPart::Skin ? 0 : 1].indices.push_back(
        static_cast<uint32_t>(skinLocal[skin.indices[t]]));
  prims[2] = fromPart(teethUpper);
  prims[3] = fromPart(teethLower);
  prims[4] = fromPart(tongue);

  DeformableHead head;
  head.eyes = {{eyeL.centre(), eyeL.radius()}, {eyeR.centre(), eyeR.radius()}};
  const HeadPart partOf[5] = {HeadPart::Skin, HeadPart::Mouth, HeadPart::TeethUpper, HeadPart::TeethLower,
                              HeadPart::Tongue};
  std::vector<std::vector<float>> jawOf(5);
  jawOf[0].resize(prims[0].positions.size());
  jawOf[1].resize(prims[1].positions.size());
  for (size_t v = 0; v < skin.vertexCount(); ++v) jawOf[skin.parts[v] == SkinPart::Skin ? 0 : 1][skinLocal[v]] = skin.jawSide[v];
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
      int8_t eye = -1;
      float slide = 0.0f;
      if (p == 0) {
        for (int e = 0; e < 2; ++e) {
          const float rho = glm::length(pos - head.eyes[e].centre);
          const float w = 1.0f - smoothstep(head.eyes[e].radius + 0.0018f, head.eyes[e].radius + 0.0045f, rho);
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

  // --- landmarks ------------------------------------------------------------------
  GeneratedHead out;
  LandmarkPoints& lm = out.landmarks;
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

  // --- action units -> morph targets ------------------------------------------------
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
  for (const ActionUnitInfo& info : actionUnits()) {
    const ActionUnitDef* def = nullptr;
    for (const ActionUnitDef& d : spec.actionUnits)
      if (d.name == info.name) def = &d;
    if (!def) return eng::makeError(eng::ErrorKind::Malformed, spec.source + ": action unit \"" + std::string(info.name) + "\" is missing");
    eng::Result<std::vector<vec3>> deltas = bakeActionUnit(*def, spec, lm, head);
    if (!deltas) return deltas.error();
    headMesh.targetNames.emplace_back(info.name);
    headMesh.defaultWeights.push_back(0.0f);

    // Normals of the deformed surfaces, over each surface's own topology.
    std::vector<vec3> skinMoved(skin.vertexCount());
    for (size_t v = 0; v < skin.vertexCount(); ++v) {
      const int p = skin.parts[v] == SkinPart::Skin ? 0 : 1;
      skinMoved[v] = skin.positions[v] + (*deltas)[prims[p].offset + skinLocal[v]];
    }
    const std::vector<vec3> skinMovedNormals = weldedNormals(skinMoved, skin.indices, skin.weldIds);
    std::vector<std::vector<vec3>> movedNormals(5);
    movedNormals[0].resize(prims[0].positions.size());
    movedNormals[1].resize(prims[1].positions.size());
    for (size_t v = 0; v < skin.vertexCount(); ++v)
      movedNormals[skin.parts[v] == SkinPart::Skin ? 0 : 1][skinLocal[v]] = skinMovedNormals[v];
    for (int p = 2; p < 5; ++p) {
      std::vector<vec3> moved(prims[p].positions.size());
      for (size_t v = 0; v < moved.size(); ++v) moved[v] = prims[p].positions[v] + (*deltas)[prims[p].offset + v];
      movedNormals[p] = weldedNormals(moved, prims[p].indices, prims[p].weldIds);
    }
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

  // --- textures and materials -------------------------------------------------
  eng::Model& model = out.model;
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
  tongueMaterial.baseColorFactor = glm::vec4(eng::srgb(176, 84, 86), 1.0f);
  tongueMaterial.roughness = 0.4f;
  eng::Material earMaterial;
  earMaterial.name = "Ear";
  earMaterial.baseColorFactor = glm::vec4(eng::srgb(232, 176, 150), 1.0f);
  earMaterial.roughness = 0.55f;
  model.materials = {skinMaterial, eyeMaterial, teethMaterial, mouthMaterial, tongueMaterial, earMaterial};
  const int materialOf[5] = {0, 3, 2, 2, 4};
  for (int p = 0; p < 5; ++p) headMesh.primitives[p].material = materialOf[p];

  // --- static meshes: eyes, ears ------------------------------------------------
  auto primitiveOf = [](const PartMesh& m, int material) {
    eng::Primitive prim;
    prim.positions = m.positions;
    prim.normals = m.normals;
    prim.texcoords = m.uvs;
    prim.indices = m.indices;
    prim.material = material;
    return prim;
  };
  eng::Mesh eyes;
  eyes.name = "Eyes";
  eyes.primitives.push_back(primitiveOf(buildEyeball(eyeL, prop), 1));
  eyes.primitives.push_back(primitiveOf(buildEyeball(eyeR, prop), 1));
  eng::Mesh ears;
  ears.name = "Ears";
  ears.primitives.push_back(primitiveOf(buildEar(1.0f), 5));
  ears.primitives.push_back(primitiveOf(buildEar(-1.0f), 5));
  // Ears have no texture coordinates worth keeping (flat colour material).
  for (eng::Primitive& prim : ears.primitives) prim.texcoords.clear();
  model.meshes = {std::move(headMesh), std::move(eyes), std::move(ears)};

  eng::Node root;
  root.name = "BuiltInHead";
  root.children = {1, 2, 3};
  model.nodes.push_back(root);
  const char* nodeNames[3] = {"Head", "Eyes", "Ears"};
  for (int m = 0; m < 3; ++m) {
    eng::Node n;
    n.name = nodeNames[m];
    n.parent = 0;
    n.mesh = m;
    model.nodes.push_back(n);
  }
  model.roots = {0};
  model.sourcePath = "generated:built-in-head";
  return out;
}

}  // namespace facial
