// Matching OBJ keyframes by position stays linear when points coincide
// (issue 37): each vertex looks at a bounded number of candidates, and a
// tolerance so large that distinct vertices would coincide is refused. Work
// is counted (tests/common/work_scaling.h).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "importers/obj_correspondence.h"
#include "importers/obj_keyframes.h"
#include "tests/common/obj_test_files.h"
#include "tests/common/test_support.h"
#include "tests/common/work_scaling.h"

namespace {

// n triangles whose 3n corners all lie on one point, each with its own vertices.
importers::ObjPolygonMesh pileOf(size_t triangles) {
  importers::ObjPolygonMesh mesh;
  mesh.positions.assign(3 * triangles, glm::vec3(0.25f));
  mesh.faceStart.push_back(0);
  for (size_t t = 0; t < triangles; ++t) {
    for (int k = 0; k < 3; ++k) mesh.corners.push_back({int(3 * t + size_t(k))});
    mesh.faceStart.push_back(uint32_t(mesh.corners.size()));
  }
  return mesh;
}

// A grid of n vertices, one unit apart.
importers::ObjPolygonMesh gridOf(size_t n) {
  importers::ObjPolygonMesh mesh = pileOf(n / 3);
  for (size_t v = 0; v < mesh.positions.size(); ++v) mesh.positions[v] = glm::vec3(float(v % 64), float(v / 64), 0.0f);
  return mesh;
}

TEST(ObjScaling, CoincidentPointsMatchInLinearWork) {
  testing_support::expectLinearWork([](size_t n) {
    const importers::ObjPolygonMesh pile = pileOf(n);
    const importers::ObjCornerMap map = importers::matchObjByPosition(pile, pile, 1e-3f);
    ASSERT_EQ(map.targetVertex.size(), pile.positions.size());
  }, 2000);
}

TEST(ObjScaling, DistinctPointsStillMatchOneToOne) {
  testing_support::expectLinearWork([](size_t n) {
    const importers::ObjPolygonMesh grid = gridOf(3 * n);
    const importers::ObjCornerMap map = importers::matchObjByPosition(grid, grid, 0.1f);
    for (size_t v = 0; v < grid.positions.size(); ++v) ASSERT_EQ(map.targetVertex[v], int32_t(v));
  }, 1000);
}

TEST(ObjScalingBadInput, AToleranceBeyondTheBoundIsRefused) {
  const auto dir = testing_support::freshTempDir("obj_huge_tolerance");
  testing_support::writeFile(dir / "neutral.obj", testing_support::GridObj{}.text());
  testing_support::writeFile(dir / "target.obj", testing_support::GridObj{}.text());
  const std::vector<importers::ObjTargetFile> targets{{"t", dir / "target.obj"}};
  auto huge = importers::importObjKeyframes(dir / "neutral.obj", targets,
                                            {.matchByPosition = true, .relativeTolerance = 0.5f});
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("tolerance 0.5 is outside (0, 0.01]"), std::string::npos) << huge.error().message;
  auto bound = importers::importObjKeyframes(dir / "neutral.obj", targets,
                                             {.matchByPosition = true, .relativeTolerance = importers::kMaxRelativeTolerance});
  EXPECT_TRUE(bound) << bound.error().message;
}

}  // namespace
