#pragma once
// The window the two windowed programs (`facial demo`, facial-editor) open,
// and how they close it. open() makes, in this order, the GLFW window, a
// Vulkan context that presents to it, the window renderer at the chosen
// quality tier (app::windowQualityOption) and the ImGui layer; each failure
// says which step failed ("window: ...", "Vulkan: ..."). finish() ends a run
// the way both programs must: the ImGui layer goes first (it holds objects
// of the context's device), then the validation check, so a run that drew
// with validation messages fails. GPU models the program uploaded through
// renderer() must be destroyed before the session.
//
//   auto session = app::WindowSession::open({.width = 1280, .height = 800, .title = "facial demo"});
//   auto gpuModel = (*session)->renderer().upload(model);
//   app::runWindowLoop((*session)->window(), (*session)->renderer(), ...);
//   if (auto clean = (*session)->finish(); !clean) return fail(clean.error().message);
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/present/imgui_layer.h"
#include "engine/vk/present/window.h"
#include "engine/vk/present/window_renderer.h"

namespace app {

struct WindowSessionOptions {
  uint32_t width = 1280, height = 800;
  std::string title;
  std::string applicationName = "facial";  // the Vulkan instance's application name
  std::string device;                      // eng::vk::ContextOptions::device (empty: FACIAL_DEVICE or the best)
  std::string quality = "auto";            // auto | fast | balanced | high
  bool timeFrames = false;                 // --profile: the renderer times each frame's steps and passes
};

class WindowSession {
 public:
  // Held by pointer: the renderer and the ImGui layer keep references to the window and the context.
  static eng::Result<std::unique_ptr<WindowSession>> open(const WindowSessionOptions& options);
  WindowSession(const WindowSession&) = delete;
  WindowSession& operator=(const WindowSession&) = delete;
  ~WindowSession();

  eng::vk::Window& window() { return *window_; }
  const eng::vk::Context& context() const { return *context_; }
  eng::vk::WindowRenderer& renderer() { return *renderer_; }
  eng::vk::ImGuiLayer& ui() { return *ui_; }

  // Closes the ImGui layer and reports the validation messages of the run
  // (an eng::ErrorKind::Device error counting them); the session is closed
  // whatever it returns.
  eng::Result<void> finish();

 private:
  WindowSession() = default;

  std::unique_ptr<eng::vk::Window> window_;
  std::optional<eng::vk::Context> context_;
  std::unique_ptr<eng::vk::WindowRenderer> renderer_;
  std::unique_ptr<eng::vk::ImGuiLayer> ui_;
};

}  // namespace app
