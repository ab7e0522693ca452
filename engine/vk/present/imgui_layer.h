#pragma once
// Dear ImGui (GLFW + Vulkan backends) on a WindowRenderer: created after the
// renderer, destroyed before it (waits for the GPU first). One per process:
// ImGui keeps a global context. Move-only through unique_ptr.
//
//   auto ui = ImGuiLayer::create(ctx, renderer, window);
//   (*ui)->beginFrame(); ImGui::Begin(...); ...; (*ui)->endFrame();
//   frame.overlay = ImGuiLayer::recorder();
#include <memory>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/present/window.h"
#include "engine/vk/present/window_renderer.h"

namespace eng::vk {

class ImGuiLayer {
 public:
  static Result<std::unique_ptr<ImGuiLayer>> create(const Context& ctx,
                                                         const WindowRenderer& renderer,
                                                         const Window& window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  void beginFrame();
  void endFrame();
  // Records the last endFrame()'s draw data inside the scene pass.
  static OverlayRecorder recorder();

 private:
  explicit ImGuiLayer(VkDevice device) : device_(device) {}
  VkDevice device_ = VK_NULL_HANDLE;
  bool glfwReady_ = false;
  bool vulkanReady_ = false;
};

}  // namespace eng::vk
