#include "engine/vk/present/imgui_layer.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <filesystem>

namespace eng::vk {
namespace {

// ImGui's built-in font has Latin-1 only: a typed line in Vietnamese (the
// Speak box) would show "?" for most of its letters. DejaVu Sans (Debian's
// fonts-dejavu-core, as the image labels use) lends Latin Extended and
// Vietnamese glyphs, merged into the built-in font so ASCII looks as before.
void addLatinExtendedGlyphs() {
  static const ImWchar kRanges[] = {0x0100, 0x024F, 0x0300, 0x036F, 0x1E00, 0x1EFF, 0};
  const char* path = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->AddFontDefault();
  if (!std::filesystem::exists(path)) return;  // the built-in font alone
  ImFontConfig merge;
  merge.MergeMode = true;
  io.Fonts->AddFontFromFileTTF(path, 13.0f, &merge, kRanges);
}

}  // namespace

Result<std::unique_ptr<ImGuiLayer>> ImGuiLayer::create(const Context& ctx,
                                                            const WindowRenderer& renderer,
                                                            const Window& window) {
  IMGUI_CHECKVERSION();
  std::unique_ptr<ImGuiLayer> layer(new ImGuiLayer(ctx.device()));
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  // A CPU rasteriser pays for each of the one-pixel feathered fringes ImGui
  // puts around every filled shape (a thin triangle touches as many pixel
  // blocks as a wide one): without them the editor's overlay took 6.2 ms of
  // lavapipe's frame instead of 8.0 (circles step a little; lines keep
  // their anti-aliasing).
  if (ctx.deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU) ImGui::GetStyle().AntiAliasedFill = false;
  addLatinExtendedGlyphs();
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
