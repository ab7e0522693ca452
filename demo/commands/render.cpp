// `facial render MODEL [--weight NAME=VALUE]... [--size WxH] [--yaw DEG]
//  [--pitch DEG] [--zoom F] [--device D] --out FILE.png`
// Renders one frame headless (lavapipe or a GPU) with the model's default
// weights, overridden by --weight, and writes a PNG.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "demo/cli_parse.h"
#include "demo/command.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "engine/scene/weights.h"
#include "engine/vk/context.h"
#include "engine/vk/framing_bounds.h"
#include "engine/vk/offscreen_renderer.h"

namespace cli {
namespace {

struct RenderOptions {
  std::string model;
  std::vector<std::string> weights;
  std::string size = "512x512";
  float yaw = 0.0f;
  float pitch = 0.0f;
  float zoom = 1.0f;
  std::string device;
  std::string out;
};

int fail(const std::string& message) {
  std::fprintf(stderr, "facial render: error: %s\n", message.c_str());
  return 1;
}

bool parseFloat(std::string_view text, float& out) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// A few names to suggest: those containing the unknown name first, then the first ones.
std::string suggestNames(const std::vector<std::string>& names, const std::string& unknown) {
  std::vector<std::string> picks;
  for (const std::string& n : names) {
    if (picks.size() < 8 && lower(n).find(lower(unknown)) != std::string::npos) picks.push_back(n);
  }
  for (const std::string& n : names) {
    if (picks.size() >= 8) break;
    if (std::find(picks.begin(), picks.end(), n) == picks.end()) picks.push_back(n);
  }
  std::string text;
  for (const std::string& n : picks) text += (text.empty() ? "" : ", ") + n;
  return text + (names.size() > picks.size() ? ", ... (" + std::to_string(names.size()) + " in all)" : "");
}

int runRender(const RenderOptions& o) {
  uint32_t width = 0, height = 0;
  if (!parseSize(o.size, width, height))
    return fail("--size '" + o.size + "' is not WxH with 1..16384 pixels per side (e.g. 512x512)");
  if (!(o.zoom > 0.0f) || !std::isfinite(o.zoom)) return fail("--zoom must be a positive number");

  auto model = eng::loadModel(o.model);
  if (!model) return fail(model.error().message);
  const eng::WeightLayout layout(*model);
  std::vector<float> weights = layout.defaults();
  for (const std::string& assignment : o.weights) {
    const size_t eq = assignment.rfind('=');
    float value = 0.0f;
    if (eq == std::string::npos || eq == 0 || !parseFloat(std::string_view(assignment).substr(eq + 1), value))
      return fail("--weight '" + assignment + "' is not NAME=VALUE with a finite number");
    const std::string name = assignment.substr(0, eq);
    if (layout.setByName(weights, name, value) == 0) {
      const std::vector<std::string> names = layout.names();
      if (names.empty()) return fail(o.model + ": has no morph targets, cannot set weight '" + name + "'");
      return fail(o.model + ": no morph target named '" + name + "'; available: " + suggestNames(names, name));
    }
  }

  eng::vk::ContextOptions contextOptions;
  contextOptions.device = o.device;
  auto ctx = eng::vk::Context::create(contextOptions);
  if (!ctx) return fail("Vulkan: " + ctx.error().message);
  auto renderer = eng::vk::OffscreenRenderer::create(*ctx, {width, height});
  if (!renderer) return fail("Vulkan: " + renderer.error().message);
  auto gpuModel = renderer->upload(*model);
  if (!gpuModel) return fail(gpuModel.error().message);

  eng::vk::SceneView view;
  view.camera = eng::vk::OrbitCamera::frame(eng::vk::framingBounds(*model), float(width) / float(height));
  view.camera.yawDegrees = o.yaw;
  view.camera.pitchDegrees = o.pitch;
  view.camera.zoom = o.zoom;
  const eng::vk::ModelInstance instance{&gpuModel.value(), glm::mat4(1.0f), weights};
  auto image = renderer->render(view, {&instance, 1});
  if (!image) return fail(o.model + ": rendering failed: " + image.error().message);
  if (auto written = eng::writePng(o.out, image->width, image->height, image->rgba8); !written)
    return fail(written.error().message);
  std::printf("wrote %s (%ux%u, %s)\n", o.out.c_str(), width, height, ctx->deviceInfo().name.c_str());
  return 0;
}

CommandRegistrar reg("render", "Render a model to a PNG, headless", [](CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  app.add_option("model", o->model, "glTF 2.0 file (.gltf or .glb)")->required();
  app.add_option("--weight,-w", o->weights, "Morph weight override NAME=VALUE (repeatable; all meshes with that target)");
  app.add_option("--size", o->size, "Image size WxH")->capture_default_str();
  app.add_option("--yaw", o->yaw, "Orbit yaw in degrees (+ = from the face's left)")->capture_default_str();
  app.add_option("--pitch", o->pitch, "Orbit pitch in degrees (+ = from above)")->capture_default_str();
  app.add_option("--zoom", o->zoom, "Zoom factor (> 1 = closer)")->capture_default_str();
  app.add_option("--device", o->device, "Vulkan device: discrete | integrated | cpu | name substring (default: FACIAL_DEVICE or automatic)");
  app.add_option("--out,-o", o->out, "Output PNG file")->required();
  return [o] { return runRender(*o); };
});

}  // namespace
}  // namespace cli
