#include "facial/runtime/graph/channel_set.h"

#include <gtest/gtest.h>

using namespace facial;

TEST(ChannelSet, ActionUnitsCarryRegionAndSide) {
  const ChannelSet set = ChannelSet::actionUnits();
  ASSERT_EQ(set.size(), actionUnits().size());
  const uint32_t blinkL = *set.find("AU45_Blink_L");
  EXPECT_EQ(set[blinkL].region, FaceRegion::Upper);
  EXPECT_EQ(set[blinkL].side, FaceSide::Left);
  EXPECT_EQ(set[*set.find("AU26_JawDrop")].region, FaceRegion::Lower);
}

TEST(ChannelSet, RawNamesTakeSideFromSuffixAndAuMetadataWhenTheyAreUnits) {
  const std::vector<std::string> names = {"eyeBlink_L", "mouthSmileRight", "jawOpen", "AU4_BrowLowerer"};
  auto set = ChannelSet::fromNames(names);
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_EQ((*set)[0].side, FaceSide::Left);
  EXPECT_FALSE((*set)[0].region.has_value());
  EXPECT_EQ((*set)[1].side, FaceSide::Right);
  EXPECT_EQ((*set)[2].side, FaceSide::Both);
  EXPECT_EQ((*set)[3].region, FaceRegion::Upper);
  EXPECT_FALSE(set->find("nope").has_value());
}

TEST(ChannelSetValidity, RejectsEmptyAndDuplicateNames) {
  const std::vector<std::string> duplicate = {"a", "b", "a"};
  auto d = ChannelSet::fromNames(duplicate);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("'a' appears twice"), std::string::npos);
  const std::vector<std::string> empty = {"a", ""};
  EXPECT_FALSE(ChannelSet::fromNames(empty).ok());
}
