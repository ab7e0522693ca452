// A deep node hierarchy, loaded from a file, is placed in one pass wherever
// every node is placed: world matrices, posed and morphed bounds (framing),
// the parts-inside-the-head test of the GPU upload (issue 37: a 589 KB chain
// of nodes never rendered when each node walked to the root). Work is
// counted (tests/common/work_scaling.h).
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/inner_face_parts.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/skeleton_pose.h"
#include "tests/common/work_scaling.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

// A chain of n nodes, each one unit above its parent and drawing its own
// copy of the quad (the upload places each mesh by its node).
eng::Model loadedChainOf(size_t n) {
  scene_test::GltfFileBuilder file = scene_test::quadWithTarget();
  const scene_test::Json mesh = file.doc["meshes"][0];
  file.doc["nodes"] = scene_test::Json::array();
  file.doc["meshes"] = scene_test::Json::array();
  for (size_t i = 0; i < n; ++i) {
    file.doc["meshes"].push_back(mesh);
    scene_test::Json node = {{"mesh", i}, {"translation", {0, 1, 0}}};
    if (i + 1 < n) node["children"] = {i + 1};
    file.doc["nodes"].push_back(node);
  }
  file.doc["scenes"] = {{{"nodes", {0}}}};
  file.doc["scene"] = 0;
  const std::vector<uint8_t> bytes = file.glbBytes();
  auto model = eng::loadModelFromBytes(bytes, "chain.glb");
  EXPECT_TRUE(model) << model.error().message;
  return model ? std::move(*model) : eng::Model{};
}

TEST(HierarchyScaling, PlacingEveryNodeOfAChainIsLinear) {
  testing_support::expectLinearWork([](size_t n) {
    const eng::Model model = loadedChainOf(n);
    ASSERT_EQ(model.nodes.size(), n);
    eng::resetWorkCount();  // the placing, not the reading
    const std::vector<glm::mat4> world = eng::restWorldMatrices(model);
    EXPECT_EQ(world.back()[3].y, float(n));
    const eng::Pose pose = eng::restPose(model);
    EXPECT_TRUE(eng::posedBounds(model, pose).valid());
    EXPECT_TRUE(eng::posedMorphedBounds(model, pose).valid());
    EXPECT_EQ(eng::partsInsideTheHead(model).size(), model.meshes.size());
  }, 1000);
}

}  // namespace
