#pragma once
// Bakes one action unit of the built-in head: each part of its definition
// moves some landmarks, pins the others it covers, and the RBF deformation of
// those control points (plus fixed far anchors, and still points ringing the
// mask where its weight reaches zero) moves the vertices its mask covers. The
// summed displacement then lets the eyelids slide over the eyeballs (vertices
// near an eyeball keep their distance to its centre), so a lid closes around
// the eye instead of cutting into it.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "bake/head/head_rig_spec.h"

namespace bake {

// Every vertex an action unit may move, with what the masks need to know.
struct DeformableHead {
  std::vector<glm::vec3> positions;
  std::vector<HeadPart> parts;
  std::vector<float> jawSide;  // 1 on the jaw side of the lip seam, 0 above it
  // Eyeballs the lids slide over (centre, radius), and per vertex the weight
  // of that constraint (0 = free) and which eyeball (index into eyes, -1 none).
  struct Eye {
    glm::vec3 centre;
    float radius;
  };
  std::vector<Eye> eyes;
  std::vector<float> lidSlide;
  std::vector<int8_t> lidEye;
};

// Resolved landmark positions (rest pose) with the facts masks need.
struct LandmarkPoints {
  std::vector<std::string> names;
  std::vector<glm::vec3> positions;
  std::vector<float> jawSide;
  int find(const std::string& name) const;
};

// Position deltas (one per DeformableHead vertex) for one action unit.
eng::Result<std::vector<glm::vec3>> bakeActionUnit(const ActionUnitDef& unit, const HeadRigSpec& spec,
                                                   const LandmarkPoints& landmarks, const DeformableHead& head);

}  // namespace bake
