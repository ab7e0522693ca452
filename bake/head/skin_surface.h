#pragma once
// The built-in head's skin: a latitude/longitude grid cast from inside the
// head onto HeadSdf, with two ring patches that form the eyelids around the
// eye openings, a lip seam (split, duplicated vertices between the mouth
// corners) and the mouth-interior pocket sewn to that seam. Skin and pocket
// together form one closed surface.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "bake/head/head_proportions.h"
#include "bake/head/head_sdf.h"

namespace bake {

enum class SkinPart : uint8_t { Skin = 0, MouthInterior = 1 };

struct SkinSurface {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  // Vertices with one weld id are one point of the surface split for texture
  // coordinates or primitives (normals are shared across them). The two
  // sides of the lip seam are distinct points.
  std::vector<uint32_t> weldIds;
  std::vector<SkinPart> parts;
  std::vector<uint32_t> indices;  // triangles; the three vertices of one share a part

  // Per-vertex facts for deformation masks and painting.
  std::vector<float> jawSide;         // 1 on the lower-lip/jaw side of the mouth, 0 above, smooth away from it
  std::vector<float> eyeSide;         // +1 left eyelid patch, -1 right, 0 elsewhere
  std::vector<float> lidRing;         // eyelid patch: 0 at its border .. 1 at the lid edge, > 1 tucked behind it
  std::vector<float> upperLid;        // eyelid patch: 1 on the upper lid, 0 on the lower
  std::vector<float> mouthDepth;      // pocket: 0 at the lip seam .. 1 at the back
  std::vector<glm::vec2> gridAngles;  // azimuth/elevation (radians) seen from the grid centre

  // Named points: "eye_L.upper_lid", "mouth.corner_R", ... (see skin_surface.cpp).
  std::map<std::string, glm::vec3> features;

  size_t vertexCount() const { return positions.size(); }
};

eng::Result<SkinSurface> buildSkinSurface(const HeadProportions& proportions, const HeadSdf& sdf);

}  // namespace bake
