// Landmarks that cannot be placed on the generated head fail generation with
// a message naming the file, the landmark and the problem.
#include <gtest/gtest.h>

#include "tests/bake/head/built_in_head.h"

namespace {

std::string generationError(bake::HeadRigSpec spec) {
  auto head = bake::generateHead(spec);
  EXPECT_FALSE(head.ok());
  return head.ok() ? "" : head.error().message;
}

bake::LandmarkDef* find(bake::HeadRigSpec& spec, const std::string& name) {
  for (bake::LandmarkDef& l : spec.landmarks)
    if (l.name == name) return &l;
  throw std::runtime_error("no landmark " + name);
}

TEST(HeadLandmarkErrors, PointWithNoSkinUnderIt) {
  bake::HeadRigSpec spec = head_testing::builtInSpec();
  find(spec, "chin")->xy = glm::vec2(0.5f, 0.5f);
  const std::string e = generationError(spec);
  EXPECT_NE(e.find("head_landmarks.json"), std::string::npos) << e;
  EXPECT_NE(e.find("landmark \"chin\""), std::string::npos) << e;
  EXPECT_NE(e.find("no skin under this point"), std::string::npos) << e;
}

TEST(HeadLandmarkErrors, UnknownFeatureListsTheKnownOnes) {
  bake::HeadRigSpec spec = head_testing::builtInSpec();
  find(spec, "lid_upper_L")->feature = "eye_L.eyelash";
  const std::string e = generationError(spec);
  EXPECT_NE(e.find("landmark \"lid_upper_L\": unknown feature \"eye_L.eyelash\""), std::string::npos) << e;
  EXPECT_NE(e.find("eye_L.upper_lid"), std::string::npos) << e;
}

TEST(HeadLandmarkErrors, CoincidentLandmarks) {
  bake::HeadRigSpec spec = head_testing::builtInSpec();
  const bake::LandmarkDef chin = *find(spec, "chin");
  bake::LandmarkDef* other = find(spec, "mentolabial");
  *other = chin;
  other->name = "mentolabial";
  const std::string e = generationError(spec);
  EXPECT_NE(e.find("closer than 0.5 mm"), std::string::npos) << e;
}

}  // namespace
