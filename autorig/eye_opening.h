#pragma once
// A scan's eyes made eyeballs, before targets are made for it. A scan's eyes
// are its skin (autorig::FaceParts::eyesInTheSkin): one surface with the
// lids, the eye painted on a ball inside them. Raising a lid over such an eye
// stretches the texels at its rim across the eye (streaks of lash and lid
// over the white), and nothing can turn it for a gaze. So, on a copy of the
// face, each such eye
//  - is cut free from its lids: the skin's triangles on the ball move to a
//    primitive of their own (a copy of the skin's material named as an eye,
//    so the parts finder takes it for an eyeball), set back a hundredth of the
//    ball's radius so a closing lid slides in front of it;
//  - gets the built-in head's eyeball behind it (scaled to the ball, a little
//    smaller still, turned to the face), which fills what a raised lid or a
//    turned eye uncovers with the white of an eye.
// An eye whose opening has nothing behind it (a head exported without its
// eyeballs: what shows through is the inside of the skin) gets the built-in
// head's eyeball in it, at the ball the parts finder estimates behind the lids.
// Faces with eyeballs of their own are left as they are.
#include <cstddef>
#include <string>
#include <vector>

#include "autorig/face_landmarks.h"
#include "autorig/face_parts.h"
#include "autorig/posed_face.h"
#include "autorig/target_transfer.h"
#include "engine/scene/model.h"

namespace autorig {

struct EyeOpening {
  size_t eyesCut = 0;       // eyes cut free from the skin (0-2)
  size_t eyesFilled = 0;    // empty openings given an eyeball (0-2)
  size_t ballVertices = 0;  // the head's eyeballs' vertices carried in
  // One line per eye ("Head: the right eye (412 vertices of the skin) cut free
  // from its lids, the built-in head's eyeball behind it"), for the report.
  std::vector<std::string> notes;
  bool changed() const { return eyesCut > 0 || eyesFilled > 0; }
};

// Changes `face` in place; `posed` and `parts` are `face`'s before the change
// (pose and find them again after it when changed()).
EyeOpening openTheEyes(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks, const FaceParts& parts,
                       const SourceFace& source);

}  // namespace autorig
