#pragma once
// How close the camera sits for a single face. Framing from the bounds fits
// the whole head (hair cap, ears, neck stump); a face reads better closer, so
// the face views zoom in on top of the bounds framing:
//  - a moving face (play, the headless demo) keeps room for the head's sway
//    and a dropped jaw;
//  - a still contact-sheet tile can fill its square from brows to chin.
namespace cli {

inline constexpr float kFaceZoom = 1.15f;
inline constexpr float kSheetTileZoom = 1.4f;

}  // namespace cli
