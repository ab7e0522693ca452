// Dataset items in flight (ItemRenderer): on two devices taking turns, several
// items outstanding, the images and labels are those of one item at a time on
// one device, in the order submitted. Validity apart: what the pipeline refuses.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/face_setup.h"
#include "dataset/dataset_spec.h"
#include "dataset/item_label.h"
#include "dataset/item_renderer.h"

namespace dataset {
namespace {

DatasetSpec smallSpec() {
  auto spec = readDatasetSpec(app::dataDirectory() / "datasets" / "example.json");
  EXPECT_TRUE(spec) << spec.error().message;
  spec->width = spec->height = 64;
  return *spec;
}

struct Made {
  std::vector<std::vector<uint8_t>> images;
  std::vector<std::string> labels;
};

// Items 0..count-1 through `renderer`, writing (keeping) the oldest whenever it is full.
Made make(ItemRenderer& renderer, const DatasetSpec& spec, uint64_t count) {
  Made made;
  const auto keepOldest = [&] {
    auto item = renderer.collect();
    ASSERT_TRUE(item) << item.error().message;
    made.images.push_back(item->image.rgba8);
    made.labels.push_back(labelJson(item->label));
  };
  for (uint64_t k = 0; k < count; ++k) {
    if (renderer.full()) keepOldest();
    auto submitted = renderer.submit(sampleItem(spec, k));
    EXPECT_TRUE(submitted) << submitted.error().message;
  }
  while (renderer.pending() > 0) keepOldest();
  return made;
}

TEST(ItemRenderer, ItemsInFlightOnTwoDevicesAreThoseMadeOneAtATime) {
  const DatasetSpec spec = smallSpec();
  auto pipelined = ItemRenderer::create(spec, 0, {.lanes = 2, .framesInFlight = 2});
  ASSERT_TRUE(pipelined) << pipelined.error().message;
  ASSERT_EQ(pipelined->laneCount(), 2u);
  auto single = ItemRenderer::create(spec, 0, {.lanes = 1, .framesInFlight = 1});
  ASSERT_TRUE(single) << single.error().message;

  constexpr uint64_t kItems = 7;  // an odd count: the lanes end unevenly
  const Made a = make(*pipelined, spec, kItems);
  const Made b = make(*single, spec, kItems);
  ASSERT_EQ(a.images.size(), kItems);
  ASSERT_EQ(b.images.size(), kItems);
  for (uint64_t k = 0; k < kItems; ++k) {
    EXPECT_EQ(a.labels[k], b.labels[k]) << "item " << k;
    EXPECT_TRUE(a.images[k] == b.images[k]) << "item " << k << ": the pixels differ";
    EXPECT_NE(a.labels[k].find(imageName(k, spec.count)), std::string::npos) << "item " << k << " out of order";
  }
  // Consecutive items are different pictures (the order check above is not vacuous).
  for (uint64_t k = 1; k < kItems; ++k) EXPECT_FALSE(a.images[k] == a.images[k - 1]) << "items " << k - 1 << ", " << k;
  EXPECT_TRUE(pipelined->checkValidation());
  EXPECT_TRUE(single->checkValidation());
}

TEST(ItemRenderer, DroppedItemsLeaveTheNextOnesAsTheyWouldBe) {
  const DatasetSpec spec = smallSpec();
  auto renderer = ItemRenderer::create(spec, 0, {.lanes = 2, .framesInFlight = 1});
  ASSERT_TRUE(renderer) << renderer.error().message;
  ASSERT_TRUE(renderer->submit(sampleItem(spec, 5)));
  ASSERT_TRUE(renderer->submit(sampleItem(spec, 6)));
  renderer->discardPending();
  EXPECT_EQ(renderer->pending(), 0u);
  EXPECT_FALSE(renderer->full());
  const Made after = make(*renderer, spec, 3);
  auto fresh = ItemRenderer::create(spec, 0, {.lanes = 1, .framesInFlight = 1});
  ASSERT_TRUE(fresh) << fresh.error().message;
  const Made expected = make(*fresh, spec, 3);
  EXPECT_EQ(after.labels, expected.labels);
  EXPECT_TRUE(after.images == expected.images);
}

TEST(ItemRendererValidity, ItRefusesMoreItemsThanItHoldsAndCollectingNone) {
  const DatasetSpec spec = smallSpec();
  auto renderer = ItemRenderer::create(spec, 0, {.lanes = 1, .framesInFlight = 1});
  ASSERT_TRUE(renderer) << renderer.error().message;
  auto none = renderer->collect();
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("no dataset item is in flight"), std::string::npos) << none.error().message;

  ASSERT_TRUE(renderer->submit(sampleItem(spec, 0)));
  EXPECT_TRUE(renderer->full());
  auto extra = renderer->submit(sampleItem(spec, 1));
  ASSERT_FALSE(extra);
  EXPECT_NE(extra.error().message.find("item 1: 1 items in flight already"), std::string::npos) << extra.error().message;
  EXPECT_EQ(renderer->pending(), 1u);
  auto item = renderer->collect();
  ASSERT_TRUE(item) << item.error().message;
  EXPECT_EQ(item->label.index, 0u);
}

TEST(ItemRendererValidity, NoFramesInFlightIsRefused) {
  const DatasetSpec spec = smallSpec();
  auto renderer = ItemRenderer::create(spec, 0, {.framesInFlight = 0});
  ASSERT_FALSE(renderer);
  EXPECT_NE(renderer.error().message.find("at least one frame in flight"), std::string::npos) << renderer.error().message;
}

}  // namespace
}  // namespace dataset
