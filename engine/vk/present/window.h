#pragma once
// A GLFW window for Vulkan (no GL context), and what the Context needs to
// present to it. Not movable: GLFW callbacks point at it.
//
//   auto window = eng::vk::Window::create({.width = 1280, .height = 800, .title = "facial"});
//   eng::vk::ContextOptions options;
//   (*window)->configureContext(options);
//   auto ctx = eng::vk::Context::create(options);
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"

struct GLFWwindow;

namespace eng::vk {

struct WindowOptions {
  int width = 1280;
  int height = 800;
  std::string title = "facial";
  bool resizable = true;
};

class Window {
 public:
  static Result<std::unique_ptr<Window>> create(const WindowOptions& options);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void pollEvents() const;
  // Blocks until an event arrives or `seconds` pass (a minimised window's idle wait).
  void waitEvents(double seconds) const;
  // In pixels; 0x0 while minimised. As the last event reported it (updated by
  // pollEvents / waitEvents): asking the X server is a round trip, and behind
  // a frame just presented by a CPU device (megabytes of image data) it waits
  // until the server has drawn it -- every frame.
  VkExtent2D framebufferExtent() const { return extent_; }
  // True once after each framebuffer resize.
  bool takeResized();
  // The keys pressed (GLFW_KEY_*) since the last call, oldest first; presses
  // past 32 a frame are dropped. Queued by a callback, because a fast
  // press+release (xdotool, a slow frame) between two polls would be missed by
  // glfwGetKey. Valid until the next pollEvents / waitEvents. ImGui, created
  // after the window, chains to the callback.
  std::span<const int> takeKeyPresses();

  // Adds the window system's instance extensions and a surface factory.
  void configureContext(ContextOptions& options) const;

 private:
  Window() = default;
  GLFWwindow* window_ = nullptr;
  bool resized_ = false;
  VkExtent2D extent_{};
  std::array<int, 32> keyPresses_{};
  uint32_t keyPressCount_ = 0;
  std::array<int, 32> takenKeys_{};
};

}  // namespace eng::vk
