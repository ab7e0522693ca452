// recordSequence with frames in flight: the PNGs and the sink get every frame
// in order and the same pixels as one frame at a time; a failure midway
// leaves no frame folder and no GIF, and the renderer still works; --profile
// names its stages.
#include "app/sequence_recorder.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "app/headless_model_renderer.h"
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
eng::Result<Recording> record(uint32_t framesInFlight, const app::SequenceOptions& options, int failAt = -1) {
  const eng::Model model = testing_support::makeSphereModel({});
  auto renderer = app::HeadlessModelRenderer::create(
      model, {.width = 48, .height = 48, .framing = eng::FramingMode::All, .framesInFlight = framesInFlight});
  if (!renderer) return renderer.error();
  eng::vk::ModelInstance instance{&renderer->gpuModel(), glm::mat4(1.0f), {}};
  std::vector<float> weights(renderer->gpuModel().weightCount());
  Recording out;
  auto summary = app::recordSequence(
      renderer->offscreen(), renderer->view(), options,
      [&](const app::FrameContext& f) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        if (int(f.index) == failAt) return eng::makeError(eng::ErrorKind::InvalidArgument, "stop here");
        for (size_t t = 0; t < weights.size(); ++t) weights[t] = 0.5f + 0.5f * std::sin(f.time * 7.0f + float(t));
        instance.weights = weights;
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      },
      [&](const app::FrameContext& f, const eng::Image& image) {
        out.order.push_back(f.index);
        out.pixels.push_back(image.rgba8);
      });
  EXPECT_TRUE(renderer->checkValidation());
  // The renderer is whole after a failed sequence: nothing left in flight.
  EXPECT_EQ(renderer->offscreen().pendingFrames(), 0u);
  EXPECT_TRUE(renderer->render(weights)) << "rendering after the sequence";
  if (!summary) return summary.error();
  return out;
}

TEST(SequenceRecorder, FramesInFlightKeepOrderAndPixels) {
  const auto dir = testing_support::freshTempDir("sequence_in_flight");
  app::SequenceOptions options{.framesPerSecond = 10, .seconds = 0.8f, .frameDir = dir / "frames"};
  auto serial = record(1, options);
  ASSERT_TRUE(serial) << serial.error().message;
  options.frameDir = dir / "frames3";
  auto pipelined = record(app::kSequenceFramesInFlight, options);
  ASSERT_TRUE(pipelined) << pipelined.error().message;
  const std::vector<uint32_t> expected{0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(serial->order, expected);
  EXPECT_EQ(pipelined->order, expected);
  ASSERT_EQ(pipelined->pixels.size(), serial->pixels.size());
  for (size_t i = 0; i < serial->pixels.size(); ++i) EXPECT_EQ(pipelined->pixels[i], serial->pixels[i]) << i;
  EXPECT_NE(serial->pixels[0], serial->pixels[1]) << "the frames must differ, or order is not tested";
  EXPECT_TRUE(std::filesystem::exists(dir / "frames3" / app::frameFileName(7)));
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
