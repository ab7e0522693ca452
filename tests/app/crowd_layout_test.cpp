// app/crowd_layout.h: the crowd grid of the demo (windowed and headless) and
// the benchmark: ceil(sqrt(N)) columns of square cells 1.15 x the box's larger
// side, centred on the origin, filled row by row from the top left.
#include <gtest/gtest.h>

#include "app/crowd_layout.h"

namespace {

// A head-shaped box: 0.2 wide, 0.3 tall, so the cell is 0.3 x 1.15 = 0.345.
const eng::Aabb kHead{{-0.1f, 0.0f, -0.1f}, {0.1f, 0.3f, 0.1f}};
constexpr float kCell = 0.345f;

TEST(CrowdLayout, OneMemberStaysWhereItIs) {
  const auto offsets = app::crowdOffsets(1, kHead);
  ASSERT_EQ(offsets.size(), 1u);
  EXPECT_EQ(offsets[0], glm::vec3(0.0f));
  const eng::Aabb all = app::crowdBounds(offsets, kHead);
  EXPECT_EQ(all.min, kHead.min);
  EXPECT_EQ(all.max, kHead.max);
}

TEST(CrowdLayout, NineMembersFillThreeSquareRowsFromTheTopLeft) {
  const auto offsets = app::crowdOffsets(9, kHead);
  ASSERT_EQ(offsets.size(), 9u);
  // Columns and rows are the same distance apart (the larger side, not the width).
  EXPECT_NEAR(offsets[0].x, -kCell, 1e-6f);
  EXPECT_NEAR(offsets[0].y, kCell, 1e-6f);
  EXPECT_NEAR(offsets[2].x, kCell, 1e-6f);
  EXPECT_NEAR(offsets[2].y, kCell, 1e-6f);
  EXPECT_NEAR(offsets[4].x, 0.0f, 1e-6f);
  EXPECT_NEAR(offsets[4].y, 0.0f, 1e-6f);
  EXPECT_NEAR(offsets[8].x, kCell, 1e-6f);
  EXPECT_NEAR(offsets[8].y, -kCell, 1e-6f);
  for (const glm::vec3& o : offsets) EXPECT_EQ(o.z, 0.0f);
}

TEST(CrowdLayout, AnUnfilledLastRowStaysCentredAsAGrid) {
  // 5 members: 3 columns, 2 rows; the second row holds two, under the first two columns.
  const auto offsets = app::crowdOffsets(5, kHead);
  ASSERT_EQ(offsets.size(), 5u);
  EXPECT_NEAR(offsets[0].y, 0.5f * kCell, 1e-6f);
  EXPECT_NEAR(offsets[3].x, -kCell, 1e-6f);
  EXPECT_NEAR(offsets[3].y, -0.5f * kCell, 1e-6f);
  EXPECT_NEAR(offsets[4].x, 0.0f, 1e-6f);
  const eng::Aabb all = app::crowdBounds(offsets, kHead);
  EXPECT_NEAR(all.min.x, -kCell - 0.1f, 1e-6f);
  EXPECT_NEAR(all.max.x, kCell + 0.1f, 1e-6f);
  EXPECT_NEAR(all.min.y, -0.5f * kCell, 1e-6f);
  EXPECT_NEAR(all.max.y, 0.5f * kCell + 0.3f, 1e-6f);
}

TEST(CrowdLayout, ABoxWithoutExtentGetsUnitCellsAndNoBounds) {
  const auto offsets = app::crowdOffsets(4, eng::Aabb{});
  ASSERT_EQ(offsets.size(), 4u);
  EXPECT_NEAR(offsets[1].x - offsets[0].x, 1.0f, 1e-6f);
  EXPECT_NEAR(offsets[0].y - offsets[2].y, 1.0f, 1e-6f);
  EXPECT_FALSE(app::crowdBounds(offsets, eng::Aabb{}).valid());
  EXPECT_TRUE(app::crowdOffsets(0, kHead).empty());
}

}  // namespace
