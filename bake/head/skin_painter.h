#pragma once
// Colour of the built-in head's skin and of its expression detail layers,
// evaluated per texel from the rest-pose surface point under it: skin tone,
// hair, brows (strokes), lips, lash lines, blush, baked occlusion; and the
// wrinkle / colour layers that fade in with action units (alpha = coverage).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"
#include "bake/head/head_proportions.h"
#include "bake/head/head_sdf.h"
#include "bake/head/skin_surface.h"

namespace bake {

// What the painter knows about the surface under one texel.
struct SkinTexel {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  float eyeSide = 0.0f;
  float lidRing = 0.0f;
  float upperLid = 0.0f;
  float occlusion = 1.0f;  // baked per vertex (HeadSdf::occlusion), interpolated
};

// Names of the detail layers paintSkin() can produce.
const std::vector<std::string>& skinDetailLayerNames();

class SkinPainter {
 public:
  SkinPainter(const HeadProportions& proportions, const HeadSdf& sdf);

  glm::vec3 baseColour(const SkinTexel& t) const;  // linear RGB
  // Detail layer by name (see skinDetailLayerNames()): linear RGB + coverage.
  glm::vec4 detail(const std::string& layer, const SkinTexel& t) const;

 private:
  struct BrowHair {
    glm::vec2 root, tip, lo, hi;  // front-projected, left brow; lo/hi bound it
    float width, darkness;
  };
  static float browHalfWidth(float t);  // brow half-thickness along its curve
  float browCoverage(const glm::vec3& p) const;
  float lipCoverage(const glm::vec3& p) const;

  HeadProportions prop_;
  const HeadSdf& sdf_;
  std::vector<BrowHair> browHairs_;
};

struct SkinImages {
  eng::Image baseColour;
  std::vector<eng::Image> details;  // in skinDetailLayerNames() order
};

// Rasterises the skin part of `surface` into a baseSize^2 base colour texture
// and detailSize^2 layer textures. normals and occlusion: one per vertex
// (occlusion is baked per vertex because it is smooth and costly per texel).
SkinImages paintSkin(const SkinSurface& surface, const std::vector<glm::vec3>& normals,
                     const std::vector<float>& occlusion, const SkinPainter& painter, int baseSize, int detailSize);

}  // namespace bake
