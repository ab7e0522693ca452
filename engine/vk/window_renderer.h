#pragma once
// Renders model instances into a window: swapchain (recreated on resize,
// idle while minimised), 4x MSAA, two frames in flight, an overlay hook that
// records into the same render pass after the scene (ImGui), screenshots of
// a presented frame, and shader hot reload from engine/shaders.
//
//   auto window = eng::vk::Window::create({});
//   eng::vk::ContextOptions options;
//   (*window)->configureContext(options);
//   auto ctx = eng::vk::Context::create(options);
//   auto renderer = eng::vk::WindowRenderer::create(*ctx, **window);
//   auto gpuModel = (*renderer)->upload(model);
//   // ImGui: ImGui_ImplGlfw_InitForVulkan(window->handle(), true); then fill
//   // ImGui_ImplVulkan_InitInfo from (*renderer)->imguiInfo() (see ImGuiVulkanInfo).
//   while (!(*window)->shouldClose()) {
//     (*window)->pollEvents();
//     eng::vk::FrameInput frame{view, {&instance, 1}};
//     frame.overlay = [](VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); };
//     if (auto r = (*renderer)->drawFrame(frame); !r) { /* report r.error() */ }
//   }
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/vk/buffer.h"
#include "engine/vk/context.h"
#include "engine/vk/fault_injection.h"
#include "engine/vk/gpu_image.h"
#include "engine/vk/gpu_model.h"
#include "engine/vk/render_pass.h"
#include "engine/vk/render_quality.h"
#include "engine/vk/scene_layouts.h"
#include "engine/vk/scene_renderer.h"
#include "engine/vk/scene_view.h"
#include "engine/vk/shader_library.h"
#include "engine/vk/swapchain.h"
#include "engine/vk/window.h"

namespace eng::vk {

struct WindowRendererOptions {
  // Multisampling, shadow map and shading terms (render_quality.h).
  RenderQuality quality = RenderQuality::High;
  bool vsync = true;
  bool hotReload = true;  // poll the shader sources twice a second
  std::filesystem::path shaderSourceDir = defaultShaderSourceDir();
  // Injected faults for tests (fault_injection.h); empty: FACIAL_VK_FAULTS, if set.
  std::string faults;
};

// Everything ImGui_ImplVulkan_Init needs (copy into ImGui_ImplVulkan_InitInfo;
// pass renderPass as its second argument).
struct ImGuiVulkanInfo {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;  // owned by the renderer, for ImGui's own sets
  VkRenderPass renderPass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  uint32_t minImageCount = 2;
  uint32_t imageCount = 2;
  VkSampleCountFlagBits msaaSamples = VK_SAMPLE_COUNT_1_BIT;
};

using OverlayRecorder = std::function<void(VkCommandBuffer)>;

struct FrameInput {
  SceneView view;
  std::span<const ModelInstance> instances;
  OverlayRecorder overlay;            // recorded inside the render pass after the scene
  std::filesystem::path screenshot;   // non-empty: also write this frame (overlay included) as PNG
};

enum class FrameResult { Presented, Skipped };

class WindowRenderer {
 public:
  // `ctx` must have been created with window.configureContext(); both must outlive the renderer.
  static Result<std::unique_ptr<WindowRenderer>> create(const Context& ctx, Window& window,
                                                       const WindowRendererOptions& options = {});
  ~WindowRenderer();
  WindowRenderer(const WindowRenderer&) = delete;
  WindowRenderer& operator=(const WindowRenderer&) = delete;

  Result<GpuModel> upload(const Model& model) const;
  ImGuiVulkanInfo imguiInfo() const;

  // Draws and presents one frame. Skipped while the window is minimised (after
  // a short wait for events, so a loop around it does not spin).
  Result<FrameResult> drawFrame(const FrameInput& frame);

  VkExtent2D extent() const { return swapchain_.extent(); }
  FrameStats lastFrameStats() const { return scene_.stats(lastSlot_); }
  const ShaderLibrary& shaders() const { return *shaders_; }
  // Polls the shader sources now and rebuilds pipelines if they changed and compile.
  bool reloadChangedShaders();

 private:
  static constexpr uint32_t kFramesInFlight = 2;
  struct FrameSync {
    UniqueCommandPool pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    UniqueFence inFlight;
    UniqueSemaphore imageAvailable;
  };

  WindowRenderer() = default;
  Result<void> recreateSwapchain();
  // MSAA colour, depth, framebuffers and semaphores for the current swapchain.
  Result<void> createSwapchainResources();
  Result<void> saveScreenshot(const std::filesystem::path& path);

  const Context* ctx_ = nullptr;
  Window* window_ = nullptr;
  WindowRendererOptions options_;
  std::unique_ptr<SceneLayouts> layouts_;
  std::unique_ptr<ShaderLibrary> shaders_;
  TargetFormat format_;
  UniqueRenderPass renderPass_;
  Swapchain swapchain_;
  bool swapchainStale_ = false;
  GpuImage msaaColor_;
  GpuImage depth_;
  std::vector<UniqueFramebuffer> framebuffers_;      // per swapchain image
  std::vector<UniqueSemaphore> renderFinished_;      // per swapchain image
  std::array<FrameSync, kFramesInFlight> frames_;
  SceneRenderer scene_;
  FaultInjector faults_;
  UniqueDescriptorPool imguiPool_;
  Buffer screenshotBuffer_;
  uint32_t frameIndex_ = 0;
  uint32_t lastSlot_ = 0;
  std::chrono::steady_clock::time_point lastShaderPoll_{};
};

}  // namespace eng::vk
