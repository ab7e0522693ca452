#include "app/view_options.h"

#include <cmath>

#include "app/cli_parse.h"

namespace app {

void addDeviceOption(CLI::App& app, std::string& device) {
  app.add_option("--device", device,
                 "Vulkan device: discrete | integrated | cpu | name substring (default: FACIAL_DEVICE or the best)");
}

void addFramingOption(CLI::App& app, std::string& frame) {
  app.add_option("--frame", frame,
                 "What the camera frames: face (the head and neck, found from the morph targets) or all (the whole "
                 "model)")
      ->capture_default_str();
}

eng::Result<eng::FramingMode> framingModeOption(const std::string& frame) {
  if (auto mode = eng::framingModeFromName(frame)) return *mode;
  return eng::makeError(eng::ErrorKind::InvalidArgument, "--frame '" + frame + "' is neither 'face' nor 'all'");
}

namespace {

constexpr const char* kQualityHelp =
    "Render quality: high (4x MSAA, soft key-light shadow, three highlights), balanced (the same with "
    "2x MSAA, or 1x and an edge-aware anti-aliasing pass where the device has no 2x, e.g. lavapipe) or fast (no MSAA, no shadow map, key highlight only); on a CPU rasteriser (lavapipe) "
    "balanced takes about half and fast about a third of high's frame time; auto: balanced on a CPU "
    "rasteriser, high on a GPU";

}  // namespace

void addQualityOption(CLI::App& app, std::string& quality) {
  app.add_option("--quality", quality, kQualityHelp)->capture_default_str();
}

eng::Result<std::optional<eng::vk::RenderQuality>> qualityOption(const std::string& quality) {
  if (quality == kQualityAuto) return std::optional<eng::vk::RenderQuality>{};
  if (auto tier = eng::vk::renderQualityFromName(quality)) return tier;
  return eng::makeError(eng::ErrorKind::InvalidArgument, "--quality '" + quality + "' is not auto, " + eng::nameList(eng::vk::kRenderQualityNames));
}

void addWindowQualityOption(CLI::App& app, std::string& quality) { addQualityOption(app, quality); }

eng::Result<eng::vk::RenderQuality> windowQualityOption(const std::string& quality, VkPhysicalDeviceType device) {
  auto tier = qualityOption(quality);
  if (!tier) return tier.error();
  return tier->value_or(eng::vk::defaultQuality(device));
}

void addViewOptions(CLI::App& app, ViewOptions& view) {
  app.add_option("--size", view.size, "Image size WxH")->capture_default_str();
  app.add_option("--yaw", view.yaw, "Orbit yaw in degrees (+ = from the face's left)")->capture_default_str();
  app.add_option("--pitch", view.pitch, "Orbit pitch in degrees (+ = from above)")->capture_default_str();
  app.add_option("--zoom", view.zoom, "Zoom factor (> 1 = closer)")->capture_default_str();
  addFramingOption(app, view.frame);
  addDeviceOption(app, view.device);
  addBackgroundOption(app, view.background);
  addQualityOption(app, view.quality);
}

eng::Result<HeadlessRenderOptions> headlessRenderOptions(const ViewOptions& view) {
  HeadlessRenderOptions options;
  if (!parseSize(view.size, options.width, options.height))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "--size '" + view.size + "' is not WxH with 1..16384 pixels per side (e.g. 512x512)");
  if (!(view.zoom > 0.0f) || !std::isfinite(view.zoom)) return eng::makeError(eng::ErrorKind::InvalidArgument, "--zoom must be a positive number");
  if (!std::isfinite(view.yaw) || !std::isfinite(view.pitch))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "--yaw and --pitch must be finite numbers of degrees");
  auto framing = framingModeOption(view.frame);
  if (!framing) return framing.error();
  options.framing = *framing;
  options.yawDegrees = view.yaw;
  options.pitchDegrees = view.pitch;
  options.zoom = view.zoom;
  options.device = view.device;
  auto backdrop = parseBackground(view.background);
  if (!backdrop) return backdrop.error();
  options.backdrop = *backdrop;
  auto quality = qualityOption(view.quality);
  if (!quality) return quality.error();
  options.quality = *quality;
  return options;
}

// --background ------------------------------------------------------------

void addBackgroundOption(CLI::App& app, std::string& background) {
  app.add_option("--background", background,
                 "Behind the face: studio (the default gradient), transparent (RGBA PNG, alpha from coverage) or "
                 "#RRGGBB");
}

eng::Result<eng::vk::Backdrop> parseBackground(const std::string& text) {
  eng::vk::Backdrop backdrop;
  if (text.empty() || text == "studio") return backdrop;
  if (text == "transparent") {
    backdrop.kind = eng::vk::Backdrop::Kind::Transparent;
    return backdrop;
  }
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  bool valid = text.size() == 7 && text[0] == '#';
  for (size_t i = 1; valid && i < 7; ++i) valid = hex(text[i]) >= 0;
  if (!valid)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "--background '" + text + "' is not transparent, studio or a colour #RRGGBB (e.g. #20a0ff)");
  backdrop.kind = eng::vk::Backdrop::Kind::Solid;
  for (int c = 0; c < 3; ++c)
    backdrop.srgb[c] = float(hex(text[1 + 2 * c]) * 16 + hex(text[2 + 2 * c])) / 255.0f;
  return backdrop;
}

}  // namespace app
