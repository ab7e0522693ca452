#pragma once
// A tiny face for tests that must not depend on ../shared: a square sheet
// facing +Z whose morph targets are named after FACS channels (so the rig
// mapping detects the ActionUnits scheme) plus one target no channel drives.
#include <filesystem>
#include <string>

#include "engine/scene/model.h"

namespace cli_test {

// Target order of the test face (its flat weight vector).
inline constexpr int kSmileLeft = 0;   // AU12_LipCornerPuller_L: lower left quarter bulges toward the camera
inline constexpr int kSmileRight = 1;  // AU12_LipCornerPuller_R
inline constexpr int kBrowLower = 2;   // AU4_BrowLowerer, default weight 0.3
inline constexpr int kJawDrop = 3;     // AU26_JawDrop: bottom rows move down
inline constexpr int kCustom = 4;      // "custom_shape": no channel drives it, default weight 0.4

eng::Model makeTestFace();
// Writes makeTestFace() as .glb under a fresh test directory `name`; returns its path.
std::filesystem::path writeTestFace(const std::string& name);

}  // namespace cli_test
