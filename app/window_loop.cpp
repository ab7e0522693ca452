#include "app/window_loop.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "app/stage_profile.h"
#include "engine/vk/device/vk_result.h"

namespace app {
namespace {

// One line for a frame that failed; a lost device ends the run, said plainly.
eng::Error frameError(uint64_t frame, const eng::Error& error) {
  return eng::vk::explainDeviceLost(error).prefixed("frame " + std::to_string(frame) + ": ");
}

// The stages --profile prints: the loop's own, then (WindowRendererOptions::timeFrames)
// the renderer's steps inside "draw" and its passes on the device.
std::vector<std::string> windowProfileStages() {
  std::vector<std::string> stages{"events", "frame (script, graph, UI)", "draw (upload, passes, ImGui, present)"};
  for (const char* name : eng::vk::kWindowCpuStepNames) stages.push_back(std::string("  ") + name);
  for (const char* name : eng::vk::kWindowGpuPassNames) stages.push_back(name);
  return stages;
}

void addFrameTimes(StageProfile& profile, const eng::vk::WindowFrameTimes& times) {
  constexpr size_t kFirst = 3;
  if (times.cpuTimed)
    for (size_t i = 0; i < times.cpu.size(); ++i) profile.add(kFirst + i, times.cpu[i]);
  if (times.gpuTimed)
    for (size_t i = 0; i < times.gpu.size(); ++i) profile.add(kFirst + times.cpu.size() + i, times.gpu[i]);
}

}  // namespace

eng::Result<void> runWindowLoop(eng::vk::Window& window, eng::vk::WindowRenderer& renderer,
                                const WindowLoopOptions& options,
                                const std::function<eng::Result<WindowFramePlan>(const WindowTick&)>& frame,
                                const std::function<void(const std::filesystem::path&)>& shotWritten) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  bool finalFrame = false;
  // Presented frames in the second half of a --quit-after run (after the
  // first second without one): start-up, shader JIT and the first uploads
  // excluded from the frame rate reported when the loop ends.
  const float measureFrom = options.quitAfter > 0.0f ? 0.5f * options.quitAfter : 1.0f;
  int measuredFrames = 0;
  Clock::time_point measureStart{};
  uint64_t frameNumber = 0;
  float animationTime = 0.0f;
  Clock::time_point finalSince{};
  StageProfile profile(windowProfileStages());
  auto msSince = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
  while (!window.shouldClose()) {
    const Clock::time_point polled = Clock::now();
    window.pollEvents();
    const double eventsMs = msSince(polled);
    const Clock::time_point now = Clock::now();
    WindowTick tick;
    // Clamped: a stall (window dragged, breakpoint) must not jump the animation.
    tick.dt = std::min(std::chrono::duration<float>(now - last).count(), 0.1f);
    last = now;
    tick.elapsed = std::chrono::duration<float>(now - start).count();
    animationTime += tick.dt;
    tick.animationTime = animationTime;
    if (options.quitAfter > 0.0f && tick.animationTime >= options.quitAfter && !finalFrame) {
      finalFrame = true;
      finalSince = now;
    }
    tick.finalFrame = finalFrame;

    auto plan = frame(tick);
    if (!plan) return plan.error();
    const double frameMs = msSince(now);
    if (plan->quit && !finalFrame) {
      finalFrame = true;
      finalSince = now;
    }
    const bool endsWithShot = finalFrame && !options.finalScreenshot.empty();
    const std::filesystem::path shot = endsWithShot ? options.finalScreenshot : plan->requestedShot;
    plan->input.screenshot = shot;
    const Clock::time_point drawStart = Clock::now();
    auto drawn = renderer.drawFrame(plan->input);
    ++frameNumber;
    if (!drawn) return frameError(frameNumber, drawn.error());
    const bool presented = *drawn == eng::vk::FrameResult::Presented;
    if (presented && tick.elapsed >= measureFrom && measuredFrames++ == 0) measureStart = Clock::now();
    if (measuredFrames > 0) {  // the frames drawn since the fps line's clock started
      profile.add(0, eventsMs);
      profile.add(1, frameMs);
      profile.add(2, msSince(drawStart));
      addFrameTimes(profile, renderer.lastFrameTimes());
      profile.endFrame();
    }
    if (!shot.empty() && presented) {
      std::printf("screenshot: %s\n", shot.c_str());
      shotWritten(shot);
    }
    // The last frame must really be drawn (not skipped while minimised) to
    // end with its screenshot; give up on that after five seconds.
    if (finalFrame && (presented || !endsWithShot || std::chrono::duration<float>(Clock::now() - finalSince).count() > 5.0f))
      break;
  }
  if (measuredFrames > 1) {
    const double seconds = std::chrono::duration<double>(Clock::now() - measureStart).count();
    const VkExtent2D extent = renderer.extent();
    std::printf("window: %ux%u %d frames presented in the last %.2f s (3D view at %.2f%s): fps=%.2f\n",
                extent.width, extent.height, measuredFrames - 1, seconds, double(renderer.renderScale()),
                renderer.adaptiveScale() ? ", adaptive" : "", double(measuredFrames - 1) / seconds);
    if (options.profile) profile.print("window", seconds);
  }
  return {};
}

}  // namespace app
