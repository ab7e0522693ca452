// `facial bench frames MODEL [--size WxH] [--frames N] [--warmup N]
//  [--animate all|none] [--instances K] [--quality auto|fast|balanced|high] [--lod-error PX] [--device D]`
// Times whole headless frames on whatever Vulkan device is present: per frame
// the weights are updated (--animate all: every morph target re-weighted by
// its own smooth sine, all of them active; none: all zero), K instances are
// drawn (one instanced draw per primitive) and the frame is finished (the
// GPU waited for; no read-back). Prints the settings, then ONE result line
// ending with fps=<median-based fps> (before it a `memory:` line: the asset's
// device buffers and what one more instance adds):
//   bench frames facecap.glb 512x512 quality=high msaa=4 instances=1 animate=all targets=52 triangles=..
//   device=llvmpipe cpu_median_ms=.. cpu_p95_ms=.. [gpu_median_ms=.. gpu_p95_ms=..] fps=..
// GPU times come from timestamps at the start and end of the frame's command
// buffer, where the device has them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "app/cli_parse.h"
#include "cli/command.h"
#include "app/face_setup.h"
#include "app/headless_model_renderer.h"
#include "app/view_options.h"
#include "app/crowd_layout.h"
#include "app/program_error.h"
#include "engine/scene/weights.h"
#include "engine/view/framing_bounds.h"
#include "engine/vk/draw/gpu_types.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::bench_command {
namespace {

struct BenchFramesOptions {
  std::string model;
  std::string size = "512x512";
  int frames = 100;
  int warmup = 10;
  std::string animate = "all";
  int instances = 1;
  std::string device;
  std::string quality = "high";
  float lodError = 0.0f;
};

// The peer framing: 30 degree vertical field of view, camera on +Z at 1.6x
// the box diagonal from its centre.
constexpr float kFovYDegrees = 30.0f;
constexpr float kDistanceInDiagonals = 1.6f;
constexpr int kMaxInstances = 4096;
constexpr int kMaxFrames = 1000000;

constexpr app::ErrorReporter fail{"facial bench frames"};

// The q-quantile (0..1) of `samples` by nearest rank; sorts them.
double quantile(std::vector<double>& samples, double q) {
  std::sort(samples.begin(), samples.end());
  const size_t rank = size_t(std::ceil(q * double(samples.size())));
  return samples[std::clamp<size_t>(rank, 1, samples.size()) - 1];
}

// Every target moves every frame with its own frequency and phase, and stays
// inside [0.05, 0.95]: all targets active, none at rest.
void animateWeights(std::vector<float>& weights, double seconds) {
  for (size_t i = 0; i < weights.size(); ++i) {
    const double hz = 0.3 + 0.07 * double(i % 13);
    const double phase = 0.61 * double(i);
    weights[i] = float(0.5 + 0.45 * std::sin(2.0 * M_PI * hz * seconds + phase));
  }
}

std::string format(double ms) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", ms);
  return text;
}

// The options' ranges; 0 when they hold, else the exit code after the error line.
int checkOptions(const BenchFramesOptions& o, uint32_t& width, uint32_t& height) {
  if (!app::parseSize(o.size, width, height)) return fail("--size '" + o.size + "' is not WxH with 1..16384 pixels a side");
  if (o.frames < 1 || o.frames > kMaxFrames)
    return fail("--frames " + std::to_string(o.frames) + " is out of range (1.." + std::to_string(kMaxFrames) + ")");
  if (o.warmup < 0 || o.warmup > kMaxFrames)
    return fail("--warmup " + std::to_string(o.warmup) + " is out of range (0.." + std::to_string(kMaxFrames) + ")");
  if (o.instances < 1 || o.instances > kMaxInstances)
    return fail("--instances " + std::to_string(o.instances) + " is out of range (1.." +
                std::to_string(kMaxInstances) + ")");
  if (o.animate != "all" && o.animate != "none") return fail("--animate '" + o.animate + "' is not all or none");
  if (!(o.lodError >= 0.0f && o.lodError <= 64.0f)) {
    char value[32];
    std::snprintf(value, sizeof(value), "%g", double(o.lodError));
    return fail(std::string("--lod-error ") + value + " is out of range (0..64 pixels)");
  }
  return 0;
}

// The report: the settings and what one frame drew, the memory, and the one
// line of timings the benchmark scripts read.
void printResults(const BenchFramesOptions& o, uint32_t width, uint32_t height, app::HeadlessModelRenderer& renderer,
                  uint32_t count, size_t targets, std::vector<double>& cpuMs, std::vector<double>& gpuMs) {
  eng::vk::OffscreenRenderer& offscreen = renderer.offscreen();
  const eng::vk::SceneView& view = renderer.view();
  const eng::vk::FrameStats stats = offscreen.lastFrameStats();
  const eng::vk::RenderQuality quality = offscreen.quality();  // "auto" resolved by the device
  const eng::vk::QualitySettings tier = eng::vk::qualitySettings(quality);
  std::printf("settings: quality=%s msaa=%d shadow_map=%u shadow_taps=%u secondary_specular=%s backdrop=studio "
              "camera=fov%.0f@%.1fxdiagonal camera_target=%g,%g,%g camera_distance=%g draws=%u active_weights=%u "
              "lod_error=%g triangles=%llu coarser_draws=%u timestamps=%s\n",
              std::string(eng::vk::renderQualityName(quality)).c_str(), int(offscreen.samples()), tier.shadowMapSize,
              tier.shadowMapSize > 0 ? (2 * tier.shadowFilterRadius + 1) * (2 * tier.shadowFilterRadius + 1) : 0u,
              tier.secondarySpecular ? "on" : "off", double(kFovYDegrees), double(kDistanceInDiagonals),
              double(view.camera.target.x), double(view.camera.target.y), double(view.camera.target.z),
              double(view.camera.distance), stats.draws,
              stats.activeWeights, double(o.lodError), static_cast<unsigned long long>(stats.triangles),
              stats.coarserDraws, offscreen.hasGpuTimestamps() ? "yes" : "no");
  // Memory: what the face asset holds on the device, and what one more
  // instance adds (its GPU records, active list, target weights and joint
  // matrices uploaded per frame, its morphed vertices, plus its CPU weight vector).
  const double perInstance =
      double(size_t(stats.instances) * sizeof(eng::vk::GpuInstance) +
             size_t(stats.activeWeights) * sizeof(eng::vk::ActiveWeight) + size_t(stats.jointMatrices) * sizeof(glm::mat4) +
             size_t(stats.targetWeights) * sizeof(float) + stats.morphedBytes) /
          double(count) +
      double(targets * sizeof(float));
  std::printf("memory: asset_buffer_bytes=%llu per_instance_bytes=%.0f\n",
              static_cast<unsigned long long>(renderer.gpuModel().bufferBytes()), perInstance);
  const double cpuMedian = quantile(cpuMs, 0.5);
  const double cpuP95 = quantile(cpuMs, 0.95);
  std::string line = "bench frames " + std::filesystem::path(o.model).filename().string() + " " +
                     std::to_string(width) + "x" + std::to_string(height) +
                     " quality=" + std::string(eng::vk::renderQualityName(quality)) +
                     " msaa=" + std::to_string(int(offscreen.samples())) + " instances=" + std::to_string(count) +
                     " animate=" + o.animate + " targets=" + std::to_string(targets) +
                     " triangles=" + std::to_string(stats.triangles) +
                     " device=" + renderer.deviceName() + " cpu_median_ms=" + format(cpuMedian) +
                     " cpu_p95_ms=" + format(cpuP95);
  if (gpuMs.size() == cpuMs.size()) {
    line += " gpu_median_ms=" + format(quantile(gpuMs, 0.5)) + " gpu_p95_ms=" + format(quantile(gpuMs, 0.95));
  }
  char fps[32];
  std::snprintf(fps, sizeof(fps), "%.2f", cpuMedian > 0.0 ? 1000.0 / cpuMedian : 0.0);
  std::printf("%s fps=%s\n", line.c_str(), fps);
}

int runBenchFrames(const BenchFramesOptions& o) {
  uint32_t width = 0, height = 0;
  if (const int error = checkOptions(o, width, height); error != 0) return error;
  const bool animate = o.animate == "all";
  auto quality = app::qualityOption(o.quality);
  if (!quality) return fail(quality.error().message);

  auto face = importers::loadFace(o.model, {.dressForDisplay = true});
  if (!face) return fail(face.error().message);
  const eng::Model& model = face->displayModel();
  const eng::Aabb bounds = eng::framingBounds(model, eng::FramingMode::All);
  if (!bounds.valid()) return fail(o.model + ": has no geometry to draw");

  auto renderer = app::HeadlessModelRenderer::create(
      model, {.width = width,
              .height = height,
              .framing = eng::FramingMode::All,
              .device = o.device,
              .quality = *quality,
              .lodPixelError = o.lodError});
  if (!renderer) return fail(renderer.error().message);

  // K instances side by side in a square grid, spaced by the model's size;
  // the camera frames the whole grid (one instance: the model's box).
  const uint32_t count = uint32_t(o.instances);
  const std::vector<glm::vec3> offsets = app::crowdOffsets(count, bounds);
  std::vector<glm::mat4> placements(count);
  for (uint32_t i = 0; i < count; ++i) placements[i] = glm::translate(glm::mat4(1.0f), offsets[i]);
  const eng::Aabb gridBounds = app::crowdBounds(offsets, bounds);
  eng::vk::SceneView& view = renderer->view();
  view.camera = eng::OrbitCamera::frame(gridBounds, float(width) / float(height), kFovYDegrees);
  view.camera.target = gridBounds.center();
  view.camera.distance = kDistanceInDiagonals * gridBounds.diagonal();
  view.camera.zoom = 1.0f;
  view.camera.yawDegrees = view.camera.pitchDegrees = 0.0f;

  const eng::WeightLayout layout(model);
  // All instances share one weight vector: every instance still has its own
  // record and slice of the active list, which is what the GPU path pays for.
  std::vector<float> weights(layout.total(), 0.0f);
  std::vector<eng::vk::ModelInstance> instances(count);
  for (uint32_t i = 0; i < count; ++i) instances[i] = {&renderer->gpuModel(), placements[i], weights};

  eng::vk::OffscreenRenderer& offscreen = renderer->offscreen();
  std::vector<double> cpuMs, gpuMs;
  cpuMs.reserve(size_t(o.frames));
  gpuMs.reserve(size_t(o.frames));
  constexpr double kSecondsPerFrame = 1.0 / 60.0;  // the animation's clock, not the measured one
  for (int frame = 0; frame < o.warmup + o.frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    if (animate) animateWeights(weights, double(frame) * kSecondsPerFrame);
    auto gpu = offscreen.renderTimed(view, instances);
    const auto end = std::chrono::steady_clock::now();
    if (!gpu) return fail(o.model + ": frame " + std::to_string(frame) + ": " + gpu.error().message);
    if (frame < o.warmup) continue;
    cpuMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    if (*gpu) gpuMs.push_back(**gpu);
  }
  if (auto clean = renderer->checkValidation(); !clean) return fail(clean.error().message);

  printResults(o, width, height, *renderer, count, layout.total(), cpuMs, gpuMs);
  return 0;
}

CommandRegistrar reg("bench", "Measure performance (bench frames: whole headless frames)", [](CLI::App& app) {
  app.require_subcommand(1);
  CLI::App* frames = app.add_subcommand("frames", "Time whole frames: weight update, instanced draw, GPU finish");
  auto o = std::make_shared<BenchFramesOptions>();
  frames->add_option("model", o->model, importers::kFaceFormatsHelp)->required();
  frames->add_option("--size", o->size, "Image size WxH (default 512x512)");
  frames->add_option("--frames", o->frames, "Measured frames (default 100)");
  frames->add_option("--warmup", o->warmup, "Unmeasured frames first (default 10)");
  frames->add_option("--animate", o->animate, "all: every target re-weighted every frame; none: all weights 0");
  frames->add_option("--instances", o->instances, "Instances drawn in one instanced draw (default 1)");
  app::addDeviceOption(*frames, o->device);
  app::addQualityOption(*frames, o->quality);
  frames->add_option("--lod-error", o->lodError,
                     "Level of detail: each draw at the coarsest level within this many pixels of the full mesh "
                     "(default 0: every triangle; the windows use 0.5 of theirs)");
  return [o] { return runBenchFrames(*o); };
});

}  // namespace
}  // namespace cli::bench_command
