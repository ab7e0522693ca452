#include "app/window_session.h"

#include "app/view_options.h"

namespace app {

WindowSession::~WindowSession() = default;

eng::Result<std::unique_ptr<WindowSession>> WindowSession::open(const WindowSessionOptions& options) {
  std::unique_ptr<WindowSession> session(new WindowSession());
  auto window = eng::vk::Window::create({.width = int(options.width), .height = int(options.height), .title = options.title});
  if (!window) return window.error().prefixed("window: ");
  session->window_ = std::move(*window);
  eng::vk::ContextOptions contextOptions;
  contextOptions.applicationName = options.applicationName;
  contextOptions.device = options.device;
  session->window_->configureContext(contextOptions);
  auto context = eng::vk::Context::create(contextOptions);
  if (!context) return context.error().prefixed("Vulkan: ");
  session->context_.emplace(std::move(*context));
  auto quality = windowQualityOption(options.quality, session->context_->deviceInfo().type);
  if (!quality) return quality.error();
  auto renderer = eng::vk::WindowRenderer::create(*session->context_, *session->window_, {.quality = *quality, .timeFrames = options.timeFrames});
  if (!renderer) return renderer.error().prefixed("Vulkan: ");
  session->renderer_ = std::move(*renderer);
  auto ui = eng::vk::ImGuiLayer::create(*session->context_, *session->renderer_, *session->window_);
  if (!ui) return ui.error();
  session->ui_ = std::move(*ui);
  return session;
}

eng::Result<void> WindowSession::finish() {
  ui_.reset();
  return context_->checkValidation();
}

}  // namespace app
