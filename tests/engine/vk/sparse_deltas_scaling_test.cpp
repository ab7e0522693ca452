// The morph delta packer (engine/vk/draw/sparse_deltas.h) visits only the
// targets that carry data (issue 37): a file listing thousands of empty
// targets over many vertices made it visit every vertex x target pair (60 KB
// took over a minute). Work is counted (tests/common/work_scaling.h).
#include "engine/vk/draw/sparse_deltas.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/crease_shading.h"
#include "tests/common/test_meshes.h"
#include "tests/common/work_scaling.h"

namespace {

using testing_support::workOf;

// A sheet of about `vertices` vertices with `emptyTargets` targets that hold
// nothing, then one that lifts the middle row.
eng::Primitive sheetWithTargets(size_t vertices, size_t emptyTargets) {
  const int side = std::max(2, int(std::lround(std::sqrt(double(vertices)))));
  eng::Primitive p = testing_support::flatSheet(side);
  p.targets.resize(emptyTargets);
  eng::MorphTarget lift;
  lift.positions.assign(p.positions.size(), glm::vec3(0.0f));
  for (int x = 0; x < side; ++x) lift.positions[size_t((side / 2) * side + x)] = glm::vec3(0, 0, 0.1f);
  p.targets.push_back(lift);
  return p;
}

TEST(SparseDeltasScaling, EmptyTargetsCostNothing) {
  // Vertices and empty targets both x4: 16x the pairs, 4x the data.
  testing_support::expectLinearWork([](size_t n) { (void)eng::vk::compactDeltas(sheetWithTargets(n, n)); }, 1024);
}

TEST(SparseDeltasScaling, MoreEmptyTargetsAddNoWork) {
  const uint64_t few = workOf([] { (void)eng::vk::compactDeltas(sheetWithTargets(4096, 10)); });
  const uint64_t many = workOf([] { (void)eng::vk::compactDeltas(sheetWithTargets(4096, 10000)); });
  EXPECT_GT(few, 0u);
  EXPECT_EQ(many, few);
}

TEST(SparseDeltasScaling, OnlyTheCarryingTargetIsPackedUnderItsOwnIndex) {
  const eng::Primitive p = sheetWithTargets(100, 300);
  const eng::vk::SparseDeltas sparse = eng::vk::compactDeltas(p);
  ASSERT_FALSE(sparse.entries.empty());
  size_t moved = 0;
  const size_t planes = sparse.hasTangents ? 3 : 2;
  for (size_t e = 0; e < sparse.entries.size(); ++e) {
    if ((e / eng::vk::kMorphSliceLanes) % planes != 0) continue;  // the position + target index plane only
    if (sparse.entries[e] == glm::vec4(0.0f)) continue;           // padding
    EXPECT_EQ(sparse.entries[e].w, 300.0f);                // a crease-only entry names it too
    moved += glm::vec3(sparse.entries[e]) != glm::vec3(0.0f);
  }
  EXPECT_EQ(moved, 10u) << "one entry per lifted vertex of the middle row";
}

TEST(SparseDeltasScaling, CreaseDarkeningHoldsNothingForEmptyTargets) {
  const eng::Primitive p = sheetWithTargets(400, 1000);
  const std::vector<std::vector<float>> darkening = eng::bakeCreaseDarkening(p);
  ASSERT_EQ(darkening.size(), p.targets.size());
  for (size_t t = 0; t + 1 < darkening.size(); ++t) ASSERT_TRUE(darkening[t].empty()) << t;
}

}  // namespace
