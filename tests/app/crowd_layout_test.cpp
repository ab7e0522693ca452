// app/crowd_layout.h: the crowd grid of the demo (windowed and headless) and
// the benchmark: ceil(sqrt(N)) columns of square cells 1.15 x the box's larger
// side, centred on the origin, filled row by row from the top left.
#include <gtest/gtest.h>

#include "app/crowd_layout.h"

#include <string>
#include <vector>

#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/graph_instance.h"

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

// Every member runs its own graph instance: a graph of many channels (a few
// megabytes of JSON) times --crowd 1024 is refused before any member is made.
TEST(CrowdBudget, PerCharacterGraphStateIsChargedBeforeTheCrowdIsMade) {
  constexpr size_t kChannels = 3000;
  std::vector<std::string> names;
  for (size_t c = 0; c < kChannels; ++c) names.push_back("c" + std::to_string(c));
  auto channels = facial::ChannelSet::fromNames(names);
  ASSERT_TRUE(channels) << channels.error().message;
  facial::GraphBuilder b(std::move(channels).value());
  b.setRoot(b.add(facial::PoseNode{.weights = std::vector<float>(kChannels, 0.0f)}));
  auto graph = b.build();
  ASSERT_TRUE(graph) << graph.error().message;
  const size_t each = facial::GraphInstance::bytesFor(**graph);
  EXPECT_GE(each, kChannels * sizeof(float));
  EXPECT_TRUE(app::checkCrowdBudget(1024, **graph));  // 12 MB: far below the default
  // A budget one byte short of 1024 characters.
  const size_t limit = 1024 * each - 1;
  EXPECT_TRUE(app::checkCrowdBudget(1023, **graph, limit));
  auto crowd = app::checkCrowdBudget(1024, **graph, limit);
  ASSERT_FALSE(crowd);
  EXPECT_EQ(crowd.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_NE(crowd.error().message.find("a crowd of 1024 characters (" + std::to_string(each) + " bytes of graph state each)"),
            std::string::npos)
      << crowd.error().message;
  EXPECT_NE(crowd.error().message.find("load budget of " + std::to_string(limit) + " bytes"), std::string::npos)
      << crowd.error().message;
}

}  // namespace
