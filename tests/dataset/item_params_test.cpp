// Item parameters depend only on the seed and the item's index.
#include <algorithm>

#include <gtest/gtest.h>

#include "dataset/item_params.h"

namespace dataset {
namespace {

DatasetSpec varied() {
  DatasetSpec spec;
  spec.count = 1000;
  spec.seed = 42;
  spec.models = {"head", "a.glb", "b.glb"};
  spec.emotions = {"neutral", "happy", "sad", "happily_surprised"};
  spec.intensity = {0.3f, 0.9f};
  spec.yaw = {-30.0f, 30.0f};
  spec.pitch = {-10.0f, 5.0f};
  spec.auMix = {.probability = 0.5f, .minUnits = 1, .maxUnits = 3, .weight = {0.2f, 0.6f}};
  spec.lights = {"studio", "left"};
  spec.backgrounds = {"studio", "#000000", "transparent"};
  return spec;
}

bool same(const ItemParams& a, const ItemParams& b) {
  if (a.extraUnits.size() != b.extraUnits.size()) return false;
  for (size_t i = 0; i < a.extraUnits.size(); ++i)
    if (a.extraUnits[i].channel != b.extraUnits[i].channel || a.extraUnits[i].weight != b.extraUnits[i].weight) return false;
  return a.index == b.index && a.model == b.model && a.emotion == b.emotion && a.intensity == b.intensity &&
         a.yaw == b.yaw && a.pitch == b.pitch && a.zoom == b.zoom && a.light == b.light && a.background == b.background;
}

TEST(ItemParams, AnItemIsTheSameWhicheverItemsCameBefore) {
  const DatasetSpec spec = varied();
  const ItemParams alone = sampleItem(spec, 617);
  for (uint64_t k = 0; k < 617; ++k) (void)sampleItem(spec, k);
  EXPECT_TRUE(same(sampleItem(spec, 617), alone));
}

TEST(ItemParams, StayInTheirRangesAndCoverThem) {
  const DatasetSpec spec = varied();
  std::vector<int> models(3), emotions(4), lights(2), backgrounds(3);
  size_t mixed = 0;
  float minYaw = 1e9f, maxYaw = -1e9f;
  for (uint64_t k = 0; k < spec.count; ++k) {
    const ItemParams item = sampleItem(spec, k);
    ASSERT_GE(item.intensity, 0.3f);
    ASSERT_LE(item.intensity, 0.9f);
    ASSERT_GE(item.pitch, -10.0f);
    ASSERT_LE(item.pitch, 5.0f);
    minYaw = std::min(minYaw, item.yaw), maxYaw = std::max(maxYaw, item.yaw);
    ++models.at(item.model), ++emotions.at(item.emotion), ++lights.at(item.light), ++backgrounds.at(item.background);
    ASSERT_LE(item.extraUnits.size(), 3u);
    for (const auto& unit : item.extraUnits) ASSERT_TRUE(unit.weight >= 0.2f && unit.weight <= 0.6f);
    mixed += item.extraUnits.empty() ? 0 : 1;
  }
  EXPECT_LT(minYaw, -25.0f);
  EXPECT_GT(maxYaw, 25.0f);
  for (int n : models) EXPECT_GT(n, 250);
  for (int n : emotions) EXPECT_GT(n, 180);
  EXPECT_GT(mixed, 400u);
  EXPECT_LT(mixed, 600u);
}

TEST(ItemParams, TheSeedChangesTheItems) {
  DatasetSpec a = varied(), b = varied();
  b.seed = 43;
  size_t differ = 0;
  for (uint64_t k = 0; k < 100; ++k) differ += sampleItem(a, k).yaw != sampleItem(b, k).yaw;
  EXPECT_GT(differ, 95u);
}

TEST(ItemParams, ThePresetScalesTheEmotionAndAddsTheMix) {
  facial::ExpressionPreset happy;
  happy.name = "happy";
  happy.actionUnits = {{3, 1.0f}, {7, 0.5f}};
  ItemParams item;
  item.intensity = 0.5f;
  item.extraUnits = {{1, 0.4f}, {7, 0.6f}};
  const facial::ExpressionPreset preset = itemPreset(happy, item);
  ASSERT_EQ(preset.actionUnits.size(), 3u);
  EXPECT_EQ(preset.actionUnits[0].channel, 1u);
  EXPECT_FLOAT_EQ(preset.actionUnits[0].weight, 0.4f);
  EXPECT_FLOAT_EQ(preset.actionUnits[1].weight, 0.5f);   // 1.0 x 0.5
  EXPECT_FLOAT_EQ(preset.actionUnits[2].weight, 0.6f);   // max(0.25, 0.6)
}

}  // namespace
}  // namespace dataset
