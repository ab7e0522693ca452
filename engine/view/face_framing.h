#pragma once
// How close the camera sits for a single face. Framing from the bounds fits
// the whole head (hair cap, ears, neck stump); a face reads better closer, so
// the face views zoom in on top of the bounds framing:
//  - a moving face (play, the headless demo) keeps room for the head's sway
//    and a dropped jaw;
//  - a still contact-sheet tile can fill its square from brows to chin.
// Both zooms stop short of cutting off the face's features (faceViewZoom).
#include "engine/scene/model.h"
#include "engine/view/framing_bounds.h"

namespace eng {

inline constexpr float kFaceZoom = 1.15f;
inline constexpr float kSheetTileZoom = 1.4f;

// `wanted` for a face view of `model`, reduced (never below 1) as far as the
// face's features need to stay in the image; other framings keep `wanted`.
inline float faceViewZoom(const eng::Model& model, eng::FramingMode mode, float wanted, float aspect) {
  if (mode != eng::FramingMode::Face) return wanted;
  return eng::zoomShowing(eng::framingBounds(model, mode), eng::faceFeatureBounds(model), wanted, aspect);
}

}  // namespace eng
