#pragma once
// How close the camera sits for a single face. Framing from the bounds fits
// the whole head (hair cap, ears, neck stump); a face reads best when the
// brows-to-chin region fills most of the picture, so the face views zoom in
// by this much on top of the bounds framing.
namespace cli {

inline constexpr float kFaceZoom = 1.4f;

}  // namespace cli
