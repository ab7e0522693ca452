// Frames in flight (OffscreenRenderer::submit / collect): a sequence rendered
// with several frames outstanding comes back in order and byte for byte the
// same as one frame at a time, transparent backdrops included; misuse is an
// error, never a wrong picture.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/vk/draw/offscreen_renderer.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

constexpr int kFrames = 7;

// Frame i's weights: each target on its own phase, so every frame differs.
std::vector<float> weightsOf(int frame, size_t count) {
  std::vector<float> w(count);
  for (size_t t = 0; t < count; ++t) w[t] = 0.5f + 0.5f * std::sin(0.9f * float(frame) + 1.7f * float(t));
  return w;
}

struct Rig {
  eng::Model model = testing_support::makeSphereModel({});
  eng::vk::OffscreenRenderer renderer;
  eng::vk::GpuModel gpu;
  eng::vk::SceneView view;
};

Rig makeRig(uint32_t framesInFlight, eng::vk::Backdrop backdrop = {}) {
  Rig rig;
  auto renderer = eng::vk::OffscreenRenderer::create(
      vk_test::context(), {.width = 64, .height = 64, .framesInFlight = framesInFlight});
  EXPECT_TRUE(renderer) << (renderer ? "" : renderer.error().message);
  if (!renderer) return rig;
  rig.renderer = std::move(*renderer);
  auto gpu = rig.renderer.upload(rig.model);
  EXPECT_TRUE(gpu) << (gpu ? "" : gpu.error().message);
  if (gpu) rig.gpu = std::move(*gpu);
  rig.view = vk_test::viewOf(rig.model.bounds());
  rig.view.backdrop = backdrop;
  return rig;
}

std::vector<eng::Image> oneAtATime(Rig& rig) {
  std::vector<eng::Image> frames;
  for (int i = 0; i < kFrames; ++i) {
    const std::vector<float> w = weightsOf(i, rig.gpu.weightCount());
    const eng::vk::ModelInstance instance{&rig.gpu, glm::mat4(1.0f), w};
    auto image = rig.renderer.render(rig.view, {&instance, 1});
    EXPECT_TRUE(image) << (image ? "" : image.error().message);
    if (image) frames.push_back(std::move(*image));
  }
  return frames;
}

// Keeps every slot busy; the weights are overwritten right after each submit
// (the renderer must have copied them).
std::vector<eng::Image> pipelined(Rig& rig) {
  std::vector<eng::Image> frames;
  std::vector<float> w;
  auto collectOne = [&] {
    auto image = rig.renderer.collect();
    EXPECT_TRUE(image) << (image ? "" : image.error().message);
    if (image) frames.push_back(std::move(*image));
  };
  for (int i = 0; i < kFrames; ++i) {
    w = weightsOf(i, rig.gpu.weightCount());
    const eng::vk::ModelInstance instance{&rig.gpu, glm::mat4(1.0f), w};
    auto submitted = rig.renderer.submit(rig.view, {&instance, 1});
    EXPECT_TRUE(submitted) << (submitted ? "" : submitted.error().message);
    std::fill(w.begin(), w.end(), 1.0f);
    if (rig.renderer.pendingFrames() == rig.renderer.framesInFlight()) collectOne();
  }
  while (rig.renderer.pendingFrames() > 0) collectOne();
  return frames;
}

void expectSameFrames(const std::vector<eng::Image>& a, const std::vector<eng::Image>& b) {
  ASSERT_EQ(a.size(), size_t(kFrames));
  ASSERT_EQ(b.size(), a.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].rgba8, b[i].rgba8) << "frame " << i;
  EXPECT_NE(a[0].rgba8, a[1].rgba8) << "the frames must differ, or order is not tested";
}

TEST(FramesInFlight, PipelinedFramesAreTheSameFramesInOrder) {
  Rig serial = makeRig(1);
  Rig three = makeRig(3);
  ASSERT_EQ(three.renderer.framesInFlight(), 3u);
  expectSameFrames(oneAtATime(serial), pipelined(three));
}

TEST(FramesInFlight, TransparentFramesAreUnpremultipliedAlike) {
  eng::vk::Backdrop clear;
  clear.kind = eng::vk::Backdrop::Kind::Transparent;
  Rig serial = makeRig(1, clear);
  Rig two = makeRig(2, clear);
  expectSameFrames(oneAtATime(serial), pipelined(two));
}

TEST(FramesInFlight, MisuseIsAnErrorAndDiscardingRecovers) {
  Rig rig = makeRig(2);
  EXPECT_FALSE(rig.renderer.collect()) << "nothing was submitted";
  const std::vector<float> w = weightsOf(0, rig.gpu.weightCount());
  const eng::vk::ModelInstance instance{&rig.gpu, glm::mat4(1.0f), w};
  ASSERT_TRUE(rig.renderer.submit(rig.view, {&instance, 1}));
  EXPECT_FALSE(rig.renderer.render(rig.view, {&instance, 1})) << "render() with a frame in flight";
  EXPECT_FALSE(rig.renderer.capture({&instance, 1}));
  ASSERT_TRUE(rig.renderer.submit(rig.view, {&instance, 1}));
  EXPECT_FALSE(rig.renderer.submit(rig.view, {&instance, 1})) << "a third frame with two slots";
  rig.renderer.discardPending();
  EXPECT_EQ(rig.renderer.pendingFrames(), 0u);
  auto image = rig.renderer.render(rig.view, {&instance, 1});
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
}

TEST(FramesInFlight, CollectedFramesSayWhereTheirTimeWent) {
  Rig rig = makeRig(2);
  const std::vector<float> w = weightsOf(0, rig.gpu.weightCount());
  const eng::vk::ModelInstance instance{&rig.gpu, glm::mat4(1.0f), w};
  ASSERT_TRUE(rig.renderer.render(rig.view, {&instance, 1}));
  EXPECT_FALSE(rig.renderer.lastFrameTimes().gpuViewMs) << "GPU passes are timed only when asked";
  rig.renderer.timeGpuPasses(true);
  ASSERT_TRUE(rig.renderer.render(rig.view, {&instance, 1}));
  const eng::vk::OffscreenFrameTimes& times = rig.renderer.lastFrameTimes();
  EXPECT_GE(times.waitMs, 0.0);
  EXPECT_GT(times.readbackMs, 0.0);
  EXPECT_EQ(times.gpuShadowMs.has_value(), rig.renderer.hasGpuTimestamps());
  EXPECT_EQ(times.gpuViewMs.has_value(), rig.renderer.hasGpuTimestamps());
  if (times.gpuViewMs) {
    EXPECT_GT(*times.gpuViewMs, 0.0);
  }
}

}  // namespace
