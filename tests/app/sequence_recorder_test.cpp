// recordSequence with frames in flight and over several devices (lanes): the
// PNGs and the sink get every frame in order and the same pixels as one frame
// at a time; a failure midway leaves no frame folder and no GIF, and the
// renderers still work; --profile names its stages.
#include "app/sequence_recorder.h"

#include <cmath>
#include <filesystem>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "app/sequence_renderers.h"
#include "app/output_paths.h"
#include "app/stage_profile.h"
#include "tests/common/test_meshes.h"
#include "tests/common/test_support.h"

namespace {

struct Recording {
  std::vector<uint32_t> order;
  std::vector<std::vector<uint8_t>> pixels;
};

// Plays the sphere's targets on their own phases (every frame differs);
// fails at frame `failAt` when it is set.
eng::Result<Recording> record(uint32_t framesInFlight, const app::SequenceOptions& options, int failAt = -1,
                              uint32_t lanes = 1) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto renderers = app::SequenceRenderers::create(
      model, {.width = 48, .height = 48, .framing = eng::FramingMode::All, .framesInFlight = framesInFlight}, lanes);
  if (!renderers) return renderers.error();
  EXPECT_EQ(renderers->laneCount(), lanes);
  eng::vk::ModelInstance instance{&renderers->gpuModel(0), glm::mat4(1.0f), {}};
  std::vector<float> weights(renderers->gpuModel(0).weightCount());
  Recording out;
  auto summary = app::recordSequence(
      renderers->lanes(), options,
      [&](const app::FrameContext& f) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        if (int(f.index) == failAt) return eng::makeError(eng::ErrorKind::InvalidArgument, "stop here");
        EXPECT_EQ(f.lane, f.index % lanes);
        instance.model = &renderers->gpuModel(f.lane);
        for (size_t t = 0; t < weights.size(); ++t) weights[t] = 0.5f + 0.5f * std::sin(f.time * 7.0f + float(t));
        instance.weights = weights;
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      },
      [&](const app::FrameContext& f, const eng::Image& image) {
        out.order.push_back(f.index);
        out.pixels.push_back(image.rgba8);
      });
  EXPECT_TRUE(renderers->checkValidation());
  // The renderers are whole after a failed sequence: nothing left in flight.
  for (uint32_t k = 0; k < lanes; ++k) {
    const app::SequenceLane lane = renderers->lanes()[k];
    EXPECT_EQ(lane.renderer->pendingFrames(), 0u) << "lane " << k;
    instance.model = &renderers->gpuModel(k);
    EXPECT_TRUE(lane.renderer->render(*lane.view, {&instance, 1})) << "rendering after the sequence, lane " << k;
  }
  if (!summary) return summary.error();
  return out;
}

// Both recordings got frames 0..frames-1 in order, with the same pixels, and
// the frames differ from one another (else order is not tested).
void expectSameFramesInOrder(const Recording& reference, const Recording& other, uint32_t frames) {
  std::vector<uint32_t> expected(frames);
  for (uint32_t i = 0; i < frames; ++i) expected[i] = i;
  EXPECT_EQ(reference.order, expected);
  EXPECT_EQ(other.order, expected);
  ASSERT_EQ(other.pixels.size(), reference.pixels.size());
  for (size_t i = 0; i < reference.pixels.size(); ++i) EXPECT_EQ(other.pixels[i], reference.pixels[i]) << i;
  for (size_t i = 1; i < reference.pixels.size(); ++i)
    EXPECT_NE(reference.pixels[i - 1], reference.pixels[i]) << "frames " << i - 1 << " and " << i << " must differ";
}

TEST(SequenceRecorder, FramesInFlightKeepOrderAndPixels) {
  const auto dir = testing_support::freshTempDir("sequence_in_flight");
  app::SequenceOptions options{.framesPerSecond = 10, .seconds = 0.8f, .frameDir = dir / "frames"};
  auto serial = record(1, options);
  ASSERT_TRUE(serial) << serial.error().message;
  options.frameDir = dir / "frames3";
  auto pipelined = record(app::kSequenceFramesInFlight, options);
  ASSERT_TRUE(pipelined) << pipelined.error().message;
  expectSameFramesInOrder(*serial, *pipelined, 8);
  EXPECT_TRUE(std::filesystem::exists(dir / "frames3" / app::frameFileName(7)));
}

TEST(SequenceRecorder, TwoDevicesTakingTurnsKeepOrderAndPixels) {
  const auto dir = testing_support::freshTempDir("sequence_lanes");
  app::SequenceOptions options{.framesPerSecond = 10, .seconds = 0.9f, .frameDir = dir / "frames"};
  auto one = record(app::kSequenceFramesInFlight, options);
  ASSERT_TRUE(one) << one.error().message;
  options.frameDir = dir / "frames2";
  auto two = record(app::kSequenceFramesInFlight, options, -1, /*lanes=*/2);
  ASSERT_TRUE(two) << two.error().message;
  expectSameFramesInOrder(*one, *two, 9);
  EXPECT_TRUE(std::filesystem::exists(dir / "frames2" / app::frameFileName(8)));
}

TEST(SequenceRecorder, TwoDevicesFailingMidwayLeaveNothingHalfWritten) {
  const auto dir = testing_support::freshTempDir("sequence_lanes_failure");
  const app::SequenceOptions options{
      .framesPerSecond = 10, .seconds = 1.0f, .frameDir = dir / "frames", .gifPath = dir / "clip.gif"};
  auto failed = record(app::kSequenceFramesInFlight, options, /*failAt=*/7, /*lanes=*/2);
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.error().message.find("stop here"), std::string::npos) << failed.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir / "clip.gif"));
  EXPECT_FALSE(std::filesystem::exists(dir / "frames" / app::frameFileName(0)));
}

TEST(SequenceRecorder, LanesOfDifferentSizesAreRefused) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto small = app::SequenceRenderers::create(model, {.width = 32, .height = 32}, 1);
  auto large = app::SequenceRenderers::create(model, {.width = 48, .height = 32}, 1);
  ASSERT_TRUE(small && large);
  const app::SequenceLane lanes[] = {small->lanes()[0], large->lanes()[0]};
  bool stepped = false;
  auto summary = app::recordSequence(lanes, {.framesPerSecond = 10, .seconds = 0.5f},
                                     [&](const app::FrameContext&) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
                                       stepped = true;
                                       return std::span<const eng::vk::ModelInstance>();
                                     });
  ASSERT_FALSE(summary);
  EXPECT_NE(summary.error().message.find("32x32 and 48x32"), std::string::npos) << summary.error().message;
  EXPECT_FALSE(stepped);
}

TEST(SequenceRenderers, ACpuRasteriserGetsTwoDevicesAGpuOne) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto renderers = app::SequenceRenderers::create(model, {.width = 32, .height = 32});
  ASSERT_TRUE(renderers) << renderers.error().message;
  auto probe = app::HeadlessModelRenderer::create(model, {.width = 8, .height = 8});
  ASSERT_TRUE(probe) << probe.error().message;
  const bool cpu = probe->deviceType() == VK_PHYSICAL_DEVICE_TYPE_CPU;
  EXPECT_EQ(renderers->laneCount(), cpu && app::usableCores() >= 2 ? 2u : 1u) << renderers->deviceName();
  EXPECT_TRUE(renderers->checkValidation());
}

TEST(SequenceRenderers, OpeningIsFinishedOnceOrDroppedCleanly) {
  const eng::Model model = testing_support::makeSphereModel({});
  { auto dropped = app::SequenceRenderers::open({.width = 32, .height = 32}, 2); }  // waits, then releases both
  auto opening = app::SequenceRenderers::open({.width = 32, .height = 32}, 2);
  auto renderers = opening.finish(model);
  ASSERT_TRUE(renderers) << renderers.error().message;
  EXPECT_EQ(renderers->laneCount(), 2u);
  auto again = opening.finish(model);
  ASSERT_FALSE(again);
  EXPECT_NE(again.error().message.find("finished already"), std::string::npos) << again.error().message;
  // A bad camera is reported when finished, by the renderers' own check.
  auto bad = app::SequenceRenderers::open({.width = 32, .height = 32, .zoom = -1.0f}).finish(model);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("zoom must be a positive number"), std::string::npos) << bad.error().message;
}

// The sphere's weights for picture k (every picture differs).
void sphereWeights(std::vector<float>& weights, int k) {
  for (size_t t = 0; t < weights.size(); ++t) weights[t] = 0.5f + 0.5f * std::sin(float(k) * 0.7f + float(t));
}

TEST(SequenceRenderers, PicturesInFlightComeBackInOrderAsRenderedOneByOne) {
  const eng::Model model = testing_support::makeSphereModel({});
  const app::HeadlessRenderOptions options{.width = 40, .height = 40, .framing = eng::FramingMode::All};
  auto single = app::SequenceRenderers::create(model, options, 1);
  ASSERT_TRUE(single) << single.error().message;
  app::HeadlessRenderOptions inFlight = options;
  inFlight.framesInFlight = 2;
  auto pipelined = app::SequenceRenderers::create(model, inFlight, 2);
  ASSERT_TRUE(pipelined) << pipelined.error().message;
  std::vector<float> weights(pipelined->gpuModel(0).weightCount());
  ASSERT_FALSE(weights.empty());

  constexpr int kPictures = 7;
  std::vector<std::vector<uint8_t>> expected, got;
  for (int k = 0; k < kPictures; ++k) {
    sphereWeights(weights, k);
    auto image = single->render(weights);
    ASSERT_TRUE(image) << image.error().message;
    expected.push_back(image->rgba8);
  }
  const auto collectOne = [&] {
    auto image = pipelined->collect();
    ASSERT_TRUE(image) << image.error().message;
    got.push_back(image->rgba8);
  };
  for (int k = 0; k < kPictures; ++k) {
    if (pipelined->full()) collectOne();
    sphereWeights(weights, k);
    ASSERT_TRUE(pipelined->submit(weights));
    sphereWeights(weights, 100 + k);  // changed at once: the submitted picture keeps its own
  }
  EXPECT_EQ(pipelined->pending(), 4u);  // two lanes, two each
  while (pipelined->pending() > 0) collectOne();
  ASSERT_EQ(got.size(), expected.size());
  for (int k = 0; k < kPictures; ++k) EXPECT_TRUE(got[k] == expected[k]) << "picture " << k;
  for (int k = 1; k < kPictures; ++k) EXPECT_FALSE(expected[k] == expected[k - 1]) << "pictures " << k - 1 << ", " << k;
  EXPECT_TRUE(single->checkValidation());
  EXPECT_TRUE(pipelined->checkValidation());
}

TEST(SequenceRenderersValidity, SubmittingWhenFullCollectingNothingAndRenderingBehindOthersAreRefused) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto renderers = app::SequenceRenderers::create(model, {.width = 16, .height = 16}, 1);
  ASSERT_TRUE(renderers) << renderers.error().message;
  std::vector<float> weights(renderers->gpuModel(0).weightCount(), 0.25f);
  auto none = renderers->collect();
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("no picture is in flight"), std::string::npos) << none.error().message;

  ASSERT_TRUE(renderers->submit(weights));
  EXPECT_TRUE(renderers->full());
  auto extra = renderers->submit(weights);
  ASSERT_FALSE(extra);
  EXPECT_NE(extra.error().message.find("1 pictures in flight already"), std::string::npos) << extra.error().message;
  auto behind = renderers->render(weights);
  ASSERT_FALSE(behind);
  EXPECT_NE(behind.error().message.find("collect them before render()"), std::string::npos) << behind.error().message;

  renderers->discardPending();
  EXPECT_EQ(renderers->pending(), 0u);
  EXPECT_FALSE(renderers->full());
  EXPECT_TRUE(renderers->render(weights));
  std::vector<float> wrong(weights.size() + 3, 0.0f);
  EXPECT_FALSE(renderers->submit(wrong));  // the renderer's own check: nothing is left pending
  EXPECT_EQ(renderers->pending(), 0u);
  EXPECT_TRUE(renderers->checkValidation());
}

TEST(SequenceRecorder, FailureMidwayLeavesNothingHalfWritten) {
  const auto dir = testing_support::freshTempDir("sequence_failure");
  const app::SequenceOptions options{
      .framesPerSecond = 10, .seconds = 1.0f, .frameDir = dir / "frames", .gifPath = dir / "clip.gif"};
  auto failed = record(app::kSequenceFramesInFlight, options, /*failAt=*/5);
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.error().message.find("stop here"), std::string::npos) << failed.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir / "frames" / app::frameFileName(0)));
  EXPECT_FALSE(std::filesystem::exists(dir / "clip.gif"));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_TRUE(std::filesystem::is_directory(entry.path()) && std::filesystem::is_empty(entry.path()))
        << "left behind: " << entry.path();
}

TEST(StageProfile, LinesNameEachMeasuredStageWithMeanAndShare) {
  app::StageProfile profile({"step", "encode", "never"});
  for (int i = 0; i < 4; ++i) {
    profile.add(0, 1.0);
    profile.add(1, 3.0);
    profile.endFrame();
  }
  // 4 frames in 0.02 s: 5 ms a frame; step 1 ms (20 %), encode 3 ms (60 %).
  const std::string text = profile.format("play", 0.02);
  EXPECT_NE(text.find("profile play: 4 frames, 5.00 ms a frame"), std::string::npos) << text;
  EXPECT_NE(text.find("step       1.000 ms   20.0 %"), std::string::npos) << text;
  EXPECT_NE(text.find("encode     3.000 ms   60.0 %"), std::string::npos) << text;
  EXPECT_EQ(text.find("never"), std::string::npos) << "a stage never measured is left out: " << text;
}

}  // namespace
