#pragma once
// A hand-built skinned glTF for the skinning tests: a 2 x 1 strip in the XY
// plane (6 vertices at x = 0, 1, 2) bent by two joints, "Hips" at the origin
// and its child "Head" at x = 1. Vertices at x = 0 follow Hips, at x = 2 Head,
// at x = 1 both half and half. Node 0 draws the mesh with skin 0; nodes 1
// and 2 are the joints. Animation "bend" turns Head from 0 to 90 degrees
// about +Z over one second (LINEAR).
#include "tests/engine/scene/gltf_test_files.h"

namespace scene_test {

struct SkinnedStripSpec {
  int jointType = kUnsignedByte;  // kUnsignedByte or kUnsignedShort
  int weightType = kFloat;        // kFloat, or kUnsignedByte / kUnsignedShort (normalized)
  bool secondInfluenceSet = false;  // JOINTS_1 / WEIGHTS_1: the weight split over two sets
  std::string interpolation = "LINEAR";
};

GltfFileBuilder skinnedStrip(const SkinnedStripSpec& spec = {});

}  // namespace scene_test
