#pragma once
// The frame loop the windowed programs (the demo, the editor) share: frame
// time clamped against stalls, --quit-after ending on a frame that was really
// presented (a minimised window skips frames) so it carries --screenshot, and
// a requested screenshot kept until a presented frame wrote it.
#include <filesystem>
#include <functional>

#include "engine/core/result.h"
#include "engine/vk/present/window.h"
#include "engine/vk/present/window_renderer.h"

namespace app {

struct WindowLoopOptions {
  // Seconds on the animation clock (WindowTick::animationTime), the one a
  // script's actions are timed on, so a scripted run on a loaded machine
  // still reaches its last action before it ends; 0 = run until the window closes.
  float quitAfter = 0.0f;
  std::filesystem::path finalScreenshot;  // written by the last frame when quitAfter ends the run
  // Print where the measured frames' time went on exit (app::StageProfile):
  // events, the program's frame (script, graph, UI) and drawing (waiting for
  // a frame slot, upload, shadow, 3D view, resolve, blit, ImGui, present).
  bool profile = false;
};

struct WindowTick {
  float dt = 0.0f;       // seconds since the last frame, at most 0.1
  float elapsed = 0.0f;  // wall-clock seconds since the loop started
  // The sum of every dt so far: the clock the animation sees. It falls
  // behind `elapsed` when frames take longer than 0.1 s, so scripted actions
  // timed on it land at the same point of a transition on a loaded machine.
  float animationTime = 0.0f;
  bool finalFrame = false;
};

struct WindowFramePlan {
  eng::vk::FrameInput input;             // what to draw (its screenshot is set by the loop)
  std::filesystem::path requestedShot;   // F12 / scripted screenshot still to write, empty when none
  bool quit = false;                     // end after this frame (it is the final one)
};

// `frame` does one frame's input, UI and animation and says what to draw;
// `shotWritten` hears of every screenshot a presented frame wrote. Returns
// ok when the window closed or the run ended, else the first error.
eng::Result<void> runWindowLoop(eng::vk::Window& window, eng::vk::WindowRenderer& renderer,
                                const WindowLoopOptions& options,
                                const std::function<eng::Result<WindowFramePlan>(const WindowTick&)>& frame,
                                const std::function<void(const std::filesystem::path&)>& shotWritten);

}  // namespace app
