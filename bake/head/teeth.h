#pragma once
// Upper and lower tooth rows of the built-in head: a band bent along the
// dental arch with scalloped biting edges, and one shared texture (enamel,
// gaps between teeth, gum). u runs along the arch, v around the band's
// cross-section; both rows map their root side to the same texels.
#include "engine/scene/model.h"
#include "bake/head/part_mesh.h"

namespace bake {

struct ToothRowShape {
  bool upper = true;
  float halfWidth = 0.02f;   // x of the row's ends
  float frontZ = 0.084f;     // z of the front surface at the middle
  float archDepth = 0.011f;  // how far back the ends curve
  float edgeY = -0.052f;     // biting edge height at the middle
  float rootY = -0.041f;     // where the row goes into the gum
  float thickness = 0.0055f;
};

// Rows placed behind the lip seam centre (the point where the closed lips meet).
ToothRowShape upperToothRow(const glm::vec3& seamCentre);
ToothRowShape lowerToothRow(const glm::vec3& seamCentre);

PartMesh buildToothRow(const ToothRowShape& shape);
eng::Image paintTeethTexture(int width, int height);

}  // namespace bake
