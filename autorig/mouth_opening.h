#pragma once
// A face made ready for a mouth that opens, before targets are made for it.
// Head scans and sculpts often have lips that are one surface (welded: the
// upper and lower lip share the vertices where they meet) and nothing inside
// the mouth. Dropping the jaw on such a face stretches a sheet of skin across
// the opening, or, where the lips are apart, shows the background through the
// head. So, on a copy of the face:
//  - welded lips are cut along the line where they meet, between the mouth
//    corners (the corners stay joined): each vertex on the seam gets a copy
//    that the lower lip's triangles use, so the lips part as separate edges;
//  - a face with nothing inside its mouth (no teeth, no tongue found) gets the
//    source's (the built-in head's mouth inside, teeth and tongue), carried in
//    by the landmark warp and moved back until the skin and the closed lips
//    hide them. They join the skin's mesh as primitives with the head's
//    materials, so they move with the head, and the transfer turns the lower
//    teeth and the tongue with the jaw as on any face that has them.
// Faces whose lips are already separate and that have teeth are left as they are.
#include <cstddef>
#include <string>
#include <vector>

#include "autorig/face_landmarks.h"
#include "autorig/face_parts.h"
#include "autorig/posed_face.h"
#include "autorig/target_transfer.h"
#include "engine/scene/model.h"

namespace autorig {

struct MouthOpening {
  size_t cutVertices = 0;  // seam vertices given a copy for the lower lip
  size_t insideVertices = 0;  // vertices of the mouth's inside, teeth and tongue carried in (0: none)
  // One line per change ("Head: lips welded along 23 vertices, cut"), or why a
  // carried in, for the autorig report.
  std::vector<std::string> notes;
  bool changed() const { return cutVertices > 0 || insideVertices > 0; }
};

// Changes `face` in place; `posed` and `parts` are `face`'s before the change
// (pose and find them again after it when changed()).
MouthOpening openTheMouth(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks,
                          const FaceParts& parts, const SourceFace& source);

}  // namespace autorig
