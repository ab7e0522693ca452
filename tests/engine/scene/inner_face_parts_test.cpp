// Which parts of a face sit inside the head (engine/scene/inner_face_parts.h),
// on a plaster head of spheres (tests/common/test_meshes.h).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/inner_face_parts.h"
#include "tests/common/test_meshes.h"

namespace {

using testing_support::addPartAsRoot;
using testing_support::makeSphereModel;
using testing_support::plasterHead;
using testing_support::whiteSphereSpec;

TEST(InnerFaceParts, EyesAndTeethInsideTheHeadAreFoundByNameAndBounds) {
  eng::Model model = plasterHead();
  // An ear named like nothing inside, and "teeth" hanging outside the head.
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "ear", {0.9f, 0, 0}, glm::vec3(0.05f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "teeth necklace", {0, -1.5f, 0}, glm::vec3(0.2f));
  const std::vector<std::vector<bool>> inside = eng::partsInsideTheHead(model);
  ASSERT_EQ(inside.size(), model.meshes.size());
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const std::string& name = model.nodes[size_t(nodeOfMesh[m])].name;
    const bool expected = name == "eyeLeft" || name == "eyeRight" || name == "teeth";
    ASSERT_EQ(inside[m].size(), model.meshes[m].primitives.size());
    for (bool flag : inside[m]) EXPECT_EQ(flag, expected) << name;
  }
}

}  // namespace
