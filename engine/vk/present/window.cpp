#include "engine/vk/present/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <mutex>
#include <utility>

#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

// glfwInit once per process, glfwTerminate when the last window closes.
std::mutex& glfwMutex() {
  static std::mutex m;
  return m;
}
int& glfwUsers() {
  static int users = 0;
  return users;
}

std::string glfwErrorText() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  return description ? std::string(description) + " (GLFW error " + std::to_string(code) + ")" : "unknown GLFW error";
}

}  // namespace

Result<std::unique_ptr<Window>> Window::create(const WindowOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    return makeError(ErrorKind::InvalidArgument, "window size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                     " must be positive");
  {
    std::lock_guard lock(glfwMutex());
    if (glfwUsers() == 0 && !glfwInit()) return makeError(ErrorKind::Device, "cannot open a window: " + glfwErrorText());
    ++glfwUsers();
  }
  std::unique_ptr<Window> w(new Window());
  if (!glfwVulkanSupported()) return makeError(ErrorKind::Device, "GLFW found no Vulkan loader with window-system support");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, options.resizable ? GLFW_TRUE : GLFW_FALSE);
  w->window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (!w->window_) return makeError(ErrorKind::Device, "cannot create a window: " + glfwErrorText());
  glfwSetWindowUserPointer(w->window_, w.get());
  int width = 0, height = 0;
  glfwGetFramebufferSize(w->window_, &width, &height);
  w->extent_ = {uint32_t(std::max(width, 0)), uint32_t(std::max(height, 0))};
  glfwSetFramebufferSizeCallback(w->window_, [](GLFWwindow* handle, int width, int height) {
    Window* self = static_cast<Window*>(glfwGetWindowUserPointer(handle));
    self->extent_ = {uint32_t(std::max(width, 0)), uint32_t(std::max(height, 0))};
    self->resized_ = true;
  });
  glfwSetKeyCallback(w->window_, [](GLFWwindow* handle, int key, int, int action, int) {
    Window* self = static_cast<Window*>(glfwGetWindowUserPointer(handle));
    if (action == GLFW_PRESS && self->keyPressCount_ < self->keyPresses_.size())
      self->keyPresses_[self->keyPressCount_++] = key;
  });
  return w;
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  std::lock_guard lock(glfwMutex());
  if (--glfwUsers() == 0) glfwTerminate();
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::pollEvents() const { glfwPollEvents(); }
void Window::waitEvents(double seconds) const { glfwWaitEventsTimeout(seconds); }

bool Window::takeResized() { return std::exchange(resized_, false); }

std::span<const int> Window::takeKeyPresses() {
  std::copy_n(keyPresses_.begin(), keyPressCount_, takenKeys_.begin());
  return {takenKeys_.data(), std::exchange(keyPressCount_, 0u)};
}

void Window::configureContext(ContextOptions& options) const {
  uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  for (uint32_t i = 0; i < count; ++i) options.instanceExtensions.emplace_back(extensions[i]);
  GLFWwindow* window = window_;
  options.createSurface = [window](VkInstance instance) -> Result<VkSurfaceKHR> {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    ENG_VK_TRY(glfwCreateWindowSurface(instance, window, nullptr, &surface));
    return surface;
  };
}

}  // namespace eng::vk
