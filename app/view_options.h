#pragma once
// The camera and device options every single-image command shares
// (`render`, `express`), declared once with one wording, and turned into
// HeadlessRenderOptions with the checks that name the bad option.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/headless_model_renderer.h"
#include "engine/core/result.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/render_quality.h"

namespace app {

struct ViewOptions {
  std::string size = "512x512";
  std::string frame = "face";
  float yaw = 0.0f;
  float pitch = 0.0f;
  float zoom = 1.0f;
  std::string device;
  std::string background;  // --background (parseBackground)
  std::string quality = "high";  // --quality (qualityOption)
};

// --device alone, for commands that choose their own framing.
void addDeviceOption(CLI::App& app, std::string& device);
// --frame face|all, for every command that shows a face (default: face).
void addFramingOption(CLI::App& app, std::string& frame);
// The --frame value as a mode; the error names the option and the value.
eng::Result<eng::FramingMode> framingModeOption(const std::string& frame);
// --quality auto|fast|balanced|high, for every command that draws a face;
// "auto" is eng::vk::defaultQuality of the device the command renders on:
// balanced on a CPU rasteriser, high on a GPU. The windows and `say` default
// to it; the still-image commands stay at high (issue 38: at 1x the judge
// reads the built-in head's fear as surprise at 384 px, and the sheets'
// edges differ; balanced's edge-aware pass did not keep the look either:
// docs/performance.md), until a cheaper anti-aliasing than 4x MSAA does.
inline constexpr const char* kQualityAuto = "auto";
void addQualityOption(CLI::App& app, std::string& quality);
// The --quality value as a tier, nullopt for "auto" (the device decides:
// HeadlessRenderOptions::quality); the error names the option and the value.
eng::Result<std::optional<eng::vk::RenderQuality>> qualityOption(const std::string& quality);
// --quality of the windows (demo, editor), the same choices.
inline constexpr const char* kWindowQualityAuto = kQualityAuto;
void addWindowQualityOption(CLI::App& app, std::string& quality);
// The window's tier once its device is known ("auto" resolved).
eng::Result<eng::vk::RenderQuality> windowQualityOption(const std::string& quality, VkPhysicalDeviceType device);
// --size --yaw --pitch --zoom --frame --device --background --quality.
void addViewOptions(CLI::App& app, ViewOptions& view);

// Size parsed, zoom/yaw/pitch checked; the error names the option and value.
eng::Result<HeadlessRenderOptions> headlessRenderOptions(const ViewOptions& view);

// --background transparent|#RRGGBB|studio: what lies behind the face. For
// commands that do not take every view option (sheet, play).
void addBackgroundOption(CLI::App& app, std::string& background);
// "" / "studio": the gradient; "transparent": RGBA with alpha from coverage;
// "#RRGGBB": that colour. The error names the option and value.
eng::Result<eng::vk::Backdrop> parseBackground(const std::string& text);

}  // namespace app
