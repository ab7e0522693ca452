#include "engine/vk/present/imgui_layer.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

namespace eng::vk {

Result<std::unique_ptr<ImGuiLayer>> ImGuiLayer::create(const Context& ctx,
                                                            const WindowRenderer& renderer,
                                                            const Window& window) {
  IMGUI_CHECKVERSION();
  std::unique_ptr<ImGuiLayer> layer(new ImGuiLayer(ctx.device()));
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  // true: ImGui chains to callbacks installed before it (the demo's key queue).
  if (!ImGui_ImplGlfw_InitForVulkan(window.handle(), true)) return makeError(ErrorKind::Device, "ImGui: GLFW backend failed to start");
  layer->glfwReady_ = true;
  const ImGuiVulkanInfo info = renderer.imguiInfo();
  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = info.instance;
  init.PhysicalDevice = info.physicalDevice;
  init.Device = info.device;
  init.QueueFamily = info.queueFamily;
  init.Queue = info.queue;
  init.DescriptorPool = info.descriptorPool;
  init.Subpass = info.subpass;
  init.MinImageCount = info.minImageCount;
  init.ImageCount = info.imageCount;
  init.MSAASamples = info.msaaSamples;
  if (!ImGui_ImplVulkan_Init(&init, info.renderPass)) return makeError(ErrorKind::Device, "ImGui: Vulkan backend failed to start");
  layer->vulkanReady_ = true;
  bool fontsOk = false;
  auto fonts = ctx.submitOneShot([&](VkCommandBuffer cmd) { fontsOk = ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  if (!fonts) return fonts.error().prefixed("ImGui fonts: ");
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  if (!fontsOk) return makeError(ErrorKind::Device, "ImGui: font texture upload failed");
  return layer;
}

ImGuiLayer::~ImGuiLayer() {
  if (device_ != VK_NULL_HANDLE) vkDeviceWaitIdle(device_);
  if (vulkanReady_) ImGui_ImplVulkan_Shutdown();
  if (glfwReady_) ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() { ImGui::Render(); }

OverlayRecorder ImGuiLayer::recorder() {
  return [](VkCommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd); };
}

}  // namespace eng::vk
