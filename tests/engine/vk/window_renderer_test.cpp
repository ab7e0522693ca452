// The window target: presenting, screenshots, resize, the ImGui overlay hook
// and hot reload in window mode. Needs a display; ctest runs these under
// xvfb-run (test vk.WindowTestsUnderXvfb).
#include "engine/vk/present/window_renderer.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <imgui.h>

#include "engine/scene/image_io.h"
#include "engine/vk/present/imgui_layer.h"
#include "tests/common/test_support.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"
#include "tests/engine/vk/x11_window_pixels.h"

namespace {

namespace fs = std::filesystem;

#define FACIAL_REQUIRE_DISPLAY()                                                                       \
  do {                                                                                                 \
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))                                    \
      GTEST_SKIP() << "no display: window tests run under xvfb-run (ctest -R vk.WindowTestsUnderXvfb)"; \
  } while (0)

// A window, its context (validation on, messages fail the test) and renderer.
struct WindowRig {
  std::unique_ptr<eng::vk::Window> window;
  std::optional<eng::vk::Context> ctx;
  std::unique_ptr<eng::vk::WindowRenderer> renderer;

  explicit WindowRig(const eng::vk::WindowRendererOptions& options = {}) {
    auto w = eng::vk::Window::create({320, 240, "test_vk window", true});
    if (!w) {
      ADD_FAILURE() << w.error().message;
      return;
    }
    window = std::move(w).value();
    eng::vk::ContextOptions contextOptions;
    contextOptions.validation = true;
    contextOptions.onValidationMessage = vk_test::failOnValidationMessage;
    window->configureContext(contextOptions);
    auto c = eng::vk::Context::create(contextOptions);
    if (!c) {
      ADD_FAILURE() << c.error().message;
      return;
    }
    ctx.emplace(std::move(c).value());
    auto r = eng::vk::WindowRenderer::create(*ctx, *window, options);
    if (!r) {
      ADD_FAILURE() << r.error().message;
      return;
    }
    renderer = std::move(r).value();
  }
  ~WindowRig() { renderer.reset(); }  // before the context
  bool ok() const { return renderer != nullptr; }
};

struct SphereScene {
  eng::Model model = testing_support::makeSphereModel({});
  std::optional<eng::vk::GpuModel> gpu;
  std::vector<float> weights = std::vector<float>(4, 0.0f);
  eng::vk::ModelInstance instance;

  explicit SphereScene(eng::vk::WindowRenderer& renderer) {
    auto uploaded = renderer.upload(model);
    if (!uploaded) {
      ADD_FAILURE() << uploaded.error().message;
      return;
    }
    gpu.emplace(std::move(uploaded).value());
    instance = {&*gpu, glm::mat4(1.0f), weights};
  }
  eng::vk::FrameInput frame() const {
    return {{eng::OrbitCamera::frame(model.bounds()), {}}, {&instance, 1}, {}, {}};
  }
};

eng::Image screenshotOf(WindowRig& rig, eng::vk::FrameInput frame, const std::string& name) {
  frame.screenshot = testing_support::freshTempDir("window_" + name) / (name + ".png");
  auto presented = rig.renderer->drawFrame(frame);
  EXPECT_TRUE(presented) << (presented ? "" : presented.error().message);
  auto image = eng::readImage(frame.screenshot);
  EXPECT_TRUE(image) << (image ? "" : image.error().message);
  return image ? std::move(image).value() : eng::Image{};
}

TEST(WindowRenderer, PresentsFramesAndSavesAScreenshot) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  for (int i = 0; i < 3; ++i) {
    rig.window->pollEvents();
    auto presented = rig.renderer->drawFrame(scene.frame());
    ASSERT_TRUE(presented) << presented.error().message;
    EXPECT_EQ(*presented, eng::vk::FrameResult::Presented);
  }
  const eng::Image shot = screenshotOf(rig, scene.frame(), "present");
  const VkExtent2D extent = rig.renderer->extent();
  ASSERT_EQ(shot.width, int(extent.width));
  ASSERT_EQ(shot.height, int(extent.height));
  const glm::ivec4 centre = vk_test::pixel(shot, shot.width / 2, shot.height / 2);
  const glm::ivec4 corner = vk_test::pixel(shot, 2, 2);
  EXPECT_GT(centre.r, corner.r + 40) << "the warm sphere in the middle, backdrop in the corner";
  EXPECT_EQ(rig.renderer->lastFrameStats().draws, 1u);
}

// What the X server shows is the frame, whichever way it got there (ctest
// runs these tests through X11 shared memory and again through the Vulkan
// swapchain: vk.WindowTestsUnderXvfb*).
TEST(WindowRenderer, TheWindowShowsTheFrame) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  const char* shm = std::getenv("FACIAL_X11_SHM");
  if (rig.ctx->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU && !(shm && std::string(shm) == "0")) {
    EXPECT_TRUE(rig.renderer->presentsThroughX11Shm()) << "a CPU device in an X11 window with MIT-SHM";
  }
  SphereScene scene(*rig.renderer);
  for (int i = 0; i < 3; ++i) {
    rig.window->pollEvents();
    ASSERT_TRUE(rig.renderer->drawFrame(scene.frame()));
  }
  const eng::Image shot = screenshotOf(rig, scene.frame(), "shown");
  ASSERT_TRUE(rig.renderer->finishPresenting());
  std::string why;
  const auto shown = vk_test::x11WindowPixels(rig.window->handle(), why);
  if (!shown) GTEST_SKIP() << "cannot read the window back: " << why;
  ASSERT_EQ(shown->width, shot.width);
  ASSERT_EQ(shown->height, shot.height);
  double sum = 0.0;
  int worst = 0;
  for (size_t i = 0; i < shot.rgba8.size(); ++i) {
    if (i % 4 == 3) continue;
    const int d = std::abs(int(shot.rgba8[i]) - int(shown->rgba8[i]));
    sum += d;
    worst = std::max(worst, d);
  }
  EXPECT_LE(worst, 1) << "mean " << sum / double(shot.rgba8.size() * 3 / 4);
  const glm::ivec4 centre = vk_test::pixel(*shown, shown->width / 2, shown->height / 2);
  EXPECT_GT(centre.r, 60) << "the sphere, not an empty window";
}

TEST(WindowRenderer, FollowsAResize) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  ASSERT_TRUE(rig.renderer->drawFrame(scene.frame()));
  glfwSetWindowSize(rig.window->handle(), 400, 300);
  for (int i = 0; i < 100 && rig.window->framebufferExtent().width != 400; ++i) {
    rig.window->pollEvents();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(rig.window->framebufferExtent().width, 400u) << "the X server applied the new size";
  const eng::Image shot = screenshotOf(rig, scene.frame(), "resized");
  EXPECT_EQ(rig.renderer->extent().width, 400u);
  EXPECT_EQ(rig.renderer->extent().height, 300u);
  EXPECT_EQ(shot.width, 400);
  EXPECT_EQ(shot.height, 300);
}

// A scaled 3D view is rendered small and blitted up: the screenshot keeps the
// window's size, and the picture matches the full-resolution one (same sphere,
// same place) apart from softer edges.
TEST(WindowRenderer, ScaledViewIsBlittedUpToTheWindow) {
  FACIAL_REQUIRE_DISPLAY();
  eng::Image shots[2];
  for (int i = 0; i < 2; ++i) {
    WindowRig rig({.renderScale = i == 0 ? 1.0f : 0.5f});
    ASSERT_TRUE(rig.ok());
    SphereScene scene(*rig.renderer);
    const VkExtent2D window = rig.renderer->extent(), view = rig.renderer->sceneExtent();
    if (i == 1) {
      ASSERT_EQ(rig.renderer->renderScale(), 0.5f) << "lavapipe's swapchain can be blitted to";
      EXPECT_EQ(view.width, (window.width + 1) / 2);
      EXPECT_EQ(view.height, (window.height + 1) / 2);
    } else {
      EXPECT_EQ(view.width, window.width);
    }
    shots[i] = screenshotOf(rig, scene.frame(), i == 0 ? "full" : "half");
    ASSERT_EQ(shots[i].width, int(window.width));
    ASSERT_EQ(shots[i].height, int(window.height));
  }
  for (auto [x, y] : {std::pair{0.5, 0.5}, std::pair{0.02, 0.02}, std::pair{0.4, 0.6}}) {
    const glm::ivec4 full = vk_test::pixel(shots[0], int(x * shots[0].width), int(y * shots[0].height));
    const glm::ivec4 half = vk_test::pixel(shots[1], int(x * shots[1].width), int(y * shots[1].height));
    EXPECT_NEAR(full.r, half.r, 12) << x << "," << y;
    EXPECT_NEAR(full.g, half.g, 12) << x << "," << y;
    EXPECT_NEAR(full.b, half.b, 12) << x << "," << y;
  }
}

// On a CPU device the automatic scale follows the frame time: whatever it
// settles on, every frame is drawn into a view of that scale's size and
// blitted to the whole window; a fixed scale (or adaptiveScale = false) stays put.
TEST(WindowRenderer, AdaptiveScaleKeepsTheViewWithinItsLimits) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  if (rig.ctx->deviceInfo().type != VK_PHYSICAL_DEVICE_TYPE_CPU) GTEST_SKIP() << "adaptive only on a CPU device";
  if (std::getenv("FACIAL_RENDER_SCALE")) GTEST_SKIP() << "FACIAL_RENDER_SCALE fixes the scale";
  ASSERT_TRUE(rig.renderer->adaptiveScale());
  SphereScene scene(*rig.renderer);
  const eng::vk::AdaptiveRenderScale::Limits limits;
  for (int i = 0; i < 3 * int(eng::vk::AdaptiveRenderScale::kWindow) + 2; ++i) {
    scene.weights[0] = float(i % 2);  // moving: a still view would be drawn sharp instead
    auto drawn = rig.renderer->drawFrame(scene.frame());
    ASSERT_TRUE(drawn) << drawn.error().message;
    rig.window->pollEvents();
  }
  const float scale = rig.renderer->renderScale();
  EXPECT_GE(scale, limits.minScale - 1e-4f);
  EXPECT_LE(scale, limits.maxScale + 1e-4f);
  scene.weights[0] = 0.5f;
  const eng::Image shot = screenshotOf(rig, scene.frame(), "adaptive");
  EXPECT_EQ(shot.width, int(rig.renderer->extent().width));
  const VkExtent2D view = rig.renderer->sceneExtent();
  EXPECT_EQ(view.width, uint32_t(float(rig.renderer->extent().width) * rig.renderer->renderScale() + 0.5f));

  WindowRig fixed({.adaptiveScale = false});
  ASSERT_TRUE(fixed.ok());
  EXPECT_FALSE(fixed.renderer->adaptiveScale());
  EXPECT_EQ(fixed.renderer->renderScale(), eng::vk::kCpuRenderScale);
  WindowRig chosen({.renderScale = 0.5f});
  ASSERT_TRUE(chosen.ok());
  EXPECT_FALSE(chosen.renderer->adaptiveScale());
}

// Nothing changed in the 3D view: the last view image is blitted again
// instead of drawn; still for a few frames, the adaptive mode draws it once at
// the window's full resolution (sharp) and keeps re-presenting that; the first
// change goes back to the adaptive scale. The picture is the one a drawn frame
// would show.
TEST(WindowRenderer, StillViewIsRepresentedAndDrawnSharp) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig({.sharpWhenStillFor = 0.0f});  // the frame count alone decides
  ASSERT_TRUE(rig.ok());
  if (!rig.renderer->adaptiveScale()) GTEST_SKIP() << "the view is blitted only with a scale (a CPU device)";
  SphereScene scene(*rig.renderer);
  auto draw = [&] {
    auto drawn = rig.renderer->drawFrame(scene.frame());
    EXPECT_TRUE(drawn) << (drawn ? "" : drawn.error().message);
    rig.window->pollEvents();
  };
  draw();
  EXPECT_FALSE(rig.renderer->lastViewReused()) << "the first frame is drawn";
  const float adaptive = rig.renderer->renderScale();
  ASSERT_LT(adaptive, 1.0f);
  draw();
  EXPECT_TRUE(rig.renderer->lastViewReused()) << "the same frame again";
  for (uint32_t i = 1; i < eng::vk::kStillFramesBeforeSharp; ++i) draw();
  EXPECT_EQ(rig.renderer->renderScale(), 1.0f) << "still long enough: drawn at full resolution";
  EXPECT_FALSE(rig.renderer->lastViewReused()) << "the sharp view is drawn once";
  EXPECT_EQ(rig.renderer->sceneExtent().width, rig.renderer->extent().width);
  const eng::Image drawnShot = screenshotOf(rig, scene.frame(), "sharp_reused");
  EXPECT_TRUE(rig.renderer->lastViewReused()) << "then re-presented";
  EXPECT_EQ(rig.renderer->renderScale(), 1.0f);

  scene.weights[0] = 1.0f;
  draw();
  EXPECT_FALSE(rig.renderer->lastViewReused()) << "a weight changed";
  EXPECT_EQ(rig.renderer->renderScale(), adaptive) << "moving again: back to the adaptive scale";
  scene.weights[0] = 0.0f;
  for (uint32_t i = 0; i < eng::vk::kStillFramesBeforeSharp; ++i) draw();
  const eng::Image redrawn = screenshotOf(rig, scene.frame(), "sharp_drawn");
  EXPECT_FALSE(rig.renderer->lastViewReused()) << "the sharp view drawn anew";
  ASSERT_EQ(redrawn.width, drawnShot.width);
  ASSERT_EQ(redrawn.height, drawnShot.height);
  EXPECT_EQ(redrawn.rgba8, drawnShot.rgba8) << "a re-presented view is the picture a drawn one shows";
}

TEST(WindowRenderer, ImGuiOverlayDrawsIntoTheScenePass) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  // The layer the demo and the editor use: both ImGui backends on this renderer.
  auto ui = eng::vk::ImGuiLayer::create(*rig.ctx, *rig.renderer, *rig.window);
  ASSERT_TRUE(ui) << ui.error().message;

  const eng::Image without = screenshotOf(rig, scene.frame(), "no_overlay");
  (*ui)->beginFrame();
  ImGui::SetNextWindowPos({10, 10});
  ImGui::SetNextWindowSize({150, 80});
  ImGui::Begin("overlay");
  ImGui::Text("hello from ImGui");
  ImGui::End();
  (*ui)->endFrame();
  eng::vk::FrameInput frame = scene.frame();
  frame.overlay = eng::vk::ImGuiLayer::recorder();
  const eng::Image with = screenshotOf(rig, frame, "overlay");
  ui->reset();  // waits for the GPU, shuts both backends down

  ASSERT_EQ(with.rgba8.size(), without.rgba8.size());
  EXPECT_NE(vk_test::pixel(with, 40, 40), vk_test::pixel(without, 40, 40)) << "the ImGui window covers (40, 40)";
  EXPECT_EQ(vk_test::pixel(with, 250, 200), vk_test::pixel(without, 250, 200)) << "the rest is the scene";
}

TEST(WindowRenderer, HotReloadsEditedShadersWhileRunning) {
  FACIAL_REQUIRE_DISPLAY();
  const fs::path dir = testing_support::freshTempDir("window_shader_sources");
  for (const auto& entry : fs::directory_iterator(eng::vk::defaultShaderSourceDir()))
    fs::copy_file(entry.path(), dir / entry.path().filename());
  eng::vk::WindowRendererOptions options;
  options.shaderSourceDir = dir;
  WindowRig rig(options);
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  ASSERT_TRUE(rig.renderer->drawFrame(scene.frame()));

  std::stringstream source;
  source << std::ifstream(dir / "background.frag").rdbuf();
  std::string text = source.str();
  const size_t end = text.rfind('}');  // main() now ends by writing magenta
  ASSERT_NE(end, std::string::npos);
  text.insert(end, "  outColor = vec4(1.0, 0.0, 1.0, 1.0);\n");
  const auto before = fs::last_write_time(dir / "background.frag");
  testing_support::writeFile(dir / "background.frag", text);
  fs::last_write_time(dir / "background.frag", before + std::chrono::seconds(2));
  // The application only keeps drawing: drawFrame polls the sources (twice a
  // second) and rebuilds the pipelines by itself. Frames are drawn until the
  // new generation is live; the deadline only bounds a broken poll.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (rig.renderer->shaders().generation() == 0 && std::chrono::steady_clock::now() < deadline) {
    rig.window->pollEvents();
    ASSERT_TRUE(rig.renderer->drawFrame(scene.frame()));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(rig.renderer->shaders().generation(), 1u) << "drawFrame picked the edited source up and recompiled once";

  const eng::Image shot = screenshotOf(rig, scene.frame(), "hot_reload");
  EXPECT_EQ(vk_test::pixel(shot, 2, 2), glm::ivec4(255, 0, 255, 255)) << "the edited backdrop shader is live";
}

}  // namespace

namespace {

// Window faults: a storm of resizes (drawn with and without the events
// processed first, so the swapchain is often out of date or suboptimal when a
// frame starts, down to 1x1), the window hidden and shown again (unmapped and
// mapped, as a window manager minimises and restores on X11) while frames
// keep being asked for. Every frame must be presented or skipped cleanly, no
// validation message may appear, and the renderer must end at the window's size.
TEST(WindowRenderer, SurvivesResizeStormsAndHideShow) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig;
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  std::mt19937 random(5);
  std::uniform_int_distribution<int> side(1, 700);
  size_t presented = 0, skipped = 0;
  for (int i = 0; i < 120; ++i) {
    if (i % 40 == 20) {
      glfwHideWindow(rig.window->handle());
      for (int hidden = 0; hidden < 5; ++hidden) {
        rig.window->pollEvents();
        auto frame = rig.renderer->drawFrame(scene.frame());
        ASSERT_TRUE(frame) << "frame while hidden: " << frame.error().message;
        (*frame == eng::vk::FrameResult::Presented ? presented : skipped) += 1;
      }
      glfwShowWindow(rig.window->handle());
    }
    const int width = i % 15 == 7 ? 1 : side(random), height = i % 15 == 7 ? 1 : side(random);
    glfwSetWindowSize(rig.window->handle(), width, height);
    if (i % 3 != 0) rig.window->pollEvents();  // else draw before the resize is even seen
    auto frame = rig.renderer->drawFrame(scene.frame());
    ASSERT_TRUE(frame) << "frame " << i << " after a resize to " << width << "x" << height << ": " << frame.error().message;
    (*frame == eng::vk::FrameResult::Presented ? presented : skipped) += 1;
  }
  EXPECT_GT(presented, 60u) << "most frames of the storm are drawn (skipped " << skipped << ")";

  glfwSetWindowSize(rig.window->handle(), 400, 300);
  for (int i = 0; i < 200 && (rig.window->framebufferExtent().width != 400 || rig.window->framebufferExtent().height != 300); ++i) {
    rig.window->pollEvents();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(rig.window->framebufferExtent().width, 400u) << "the X server applied the last size";
  const eng::Image shot = screenshotOf(rig, scene.frame(), "after_storm");
  EXPECT_EQ(rig.renderer->extent().width, 400u);
  EXPECT_EQ(rig.renderer->extent().height, 300u);
  EXPECT_EQ(shot.width, 400);
  EXPECT_EQ(shot.height, 300);
  EXPECT_EQ(rig.ctx->validationMessageCount(), 0u);
}

}  // namespace

namespace {

// Window faults lavapipe does not produce on demand, injected at chosen frames
// (engine/vk/device/fault_injection.h): an acquisition that finds the swapchain out of
// date skips its frame and the next one rebuilds the swapchain and draws; a
// lost device is an error carrying VK_ERROR_DEVICE_LOST, and the renderer still
// tears down without a validation message.
eng::vk::WindowRendererOptions injecting(const char* faults) {
  eng::vk::WindowRendererOptions options;
  options.faults = faults;
  return options;
}

TEST(WindowRenderer, InjectedOutOfDateSwapchainIsRebuiltAndDrawingGoesOn) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig(injecting("out-of-date@2,out-of-date@3,out-of-date@5"));
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  std::vector<eng::vk::FrameResult> results;
  for (int i = 0; i < 7; ++i) {
    rig.window->pollEvents();
    auto frame = rig.renderer->drawFrame(scene.frame());
    ASSERT_TRUE(frame) << "frame " << i + 1 << ": " << frame.error().message;
    results.push_back(*frame);
  }
  using eng::vk::FrameResult;
  EXPECT_EQ(results, (std::vector<FrameResult>{FrameResult::Presented, FrameResult::Skipped, FrameResult::Skipped,
                                               FrameResult::Presented, FrameResult::Skipped, FrameResult::Presented,
                                               FrameResult::Presented}))
      << "each out-of-date acquisition skips one frame, the rebuilt swapchain draws the next";
  const eng::Image shot = screenshotOf(rig, scene.frame(), "after_out_of_date");
  EXPECT_EQ(shot.width, int(rig.renderer->extent().width));
  const glm::ivec4 centre = vk_test::pixel(shot, shot.width / 2, shot.height / 2);
  EXPECT_GT(centre.r, vk_test::pixel(shot, 2, 2).r + 40) << "the sphere is drawn after the rebuilds";
  EXPECT_EQ(rig.ctx->validationMessageCount(), 0u);
}

TEST(WindowRenderer, InjectedDeviceLossIsReportedAndTearsDownCleanly) {
  FACIAL_REQUIRE_DISPLAY();
  WindowRig rig(injecting("device-lost@3"));
  ASSERT_TRUE(rig.ok());
  SphereScene scene(*rig.renderer);
  for (int i = 0; i < 2; ++i) ASSERT_TRUE(rig.renderer->drawFrame(scene.frame()));
  auto lost = rig.renderer->drawFrame(scene.frame());
  ASSERT_FALSE(lost) << "the third submission reports the device lost";
  EXPECT_EQ(lost.error().code, VK_ERROR_DEVICE_LOST);
  EXPECT_EQ(lost.error().message, "vkQueueSubmit failed: VK_ERROR_DEVICE_LOST");
  rig.renderer.reset();  // waits for the device and destroys everything it made
  EXPECT_EQ(rig.ctx->validationMessageCount(), 0u);
}

}  // namespace
