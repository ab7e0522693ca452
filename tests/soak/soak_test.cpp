// The soak: a crowd of faces, each with its own graph instance (the demo's
// tour graph: a state machine of the seven emotions, talking, blinks), driven
// the way an application drives them for hours: random triggers at random
// moments, random parameter changes, uneven frame times with hitches, the odd
// reset, and the crowd drawn headless (every frame on a GPU; on a CPU device
// every FACIAL_SOAK_DRAW_EVERY-th frame, default 20: lavapipe with validation draws the nine
// heads in about 0.4 s of CPU, and graph updates are what runs every frame anyway).
// What must hold over any number of frames:
//   - resident memory flat: after warm-up its steady growth is at most 1 % of
//     its level at the end of warm-up (see steadyGrowth: the driver takes
//     one-time steps, a late ~28 MiB allocation whose moment depends on the
//     machine's load and smaller ones as its caches fill, which a leak does not
//     look like);
//   - the heap in use (mallinfo2) flat in the same way: a small leak can fill
//     freed pages glibc keeps resident and not move the resident size at all;
//   - every channel and morph-target weight finite, every frame;
//   - not one validation message (the context runs with the layer on).
//
//   build/bin/test_soak                             the short run (ctest)
//   FACIAL_SOAK_FRAMES=100000 FACIAL_SOAK_DRAW_EVERY=50 build/bin/test_soak   the long run
//   FACIAL_SOAK_LEAK_BYTES=8192 build/bin/test_soak  leaks that many bytes a frame on purpose: the
//                                                  check must fail (it is a test that can fail)
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "importers/face_dressing.h"
#include "tests/common/test_support.h"

namespace {

constexpr uint32_t kShortRunFrames = 1200;
constexpr uint32_t kCrowd = 9;
constexpr uint32_t kImageSide = 64;
[[maybe_unused]] constexpr double kAllowedGrowth = 0.01;  // resident memory after warm-up, relative

uint32_t positiveEnv(const char* name, uint32_t fallback) {
  if (const char* text = std::getenv(name)) {
    const long value = std::strtol(text, nullptr, 10);
    if (value > 0) return uint32_t(value);
  }
  return fallback;
}

// Resident set size from /proc/self/statm (pages -> bytes).
size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  size_t sizePages = 0, residentPages = 0;
  statm >> sizePages >> residentPages;
  return residentPages * size_t(sysconf(_SC_PAGESIZE));
}

// After warm-up the run is cut into kWindows windows of equal frame count,
// each keeping its peak resident size.
constexpr uint32_t kWindows = 8;

// Steady growth after warm-up, relative to `afterWarmup`: the lower quartile
// of the rises from one window's peak to the next, times the number of windows, i.e.
// what growth at that pace would add over the run. A leak grows the memory in
// every window, so the lower quartile of the rises is its pace. A one-time step rises in one
// window and leaves it at zero: lavapipe makes one anonymous
// allocation of about 28 MiB once, at a moment set by wall-clock time and
// thread scheduling rather than by the frames (measured with the same frames
// under load: at 18, 24 and 50 s into runs of 95 s, frame 220 to 630; then
// flat for 100,000 frames), and its retained scene and shader memory takes
// smaller steps as new content arrives (a clean-clone CI run on a loaded
// machine: heap window peaks 192 213 214 221 221 221 221 221 MiB, two steps
// then flat). Forgiving only the largest rise failed that run; the median
// (steps in fewer than half of the windows) failed another: a 25 MiB step,
// then about 1 MiB in exactly half the windows (426 427 452 452 453 453 454
// 454 MiB). So the pace is the lower quartile of the rises: it forgives
// steps in up to three windows of four, and a leak, which rises in every
// window, still sets it (FACIAL_SOAK_LEAK_BYTES=8192 fails).
double steadyGrowth(size_t afterWarmup, const std::vector<size_t>& windowPeaks, size_t& largestRise) {
  size_t previous = afterWarmup;
  largestRise = 0;
  std::vector<size_t> rises;
  for (size_t peak : windowPeaks) {
    if (peak == 0) continue;  // a window without a sample (very short runs)
    const size_t rise = peak > previous ? peak - previous : 0;
    rises.push_back(rise);
    largestRise = std::max(largestRise, rise);
    previous = std::max(previous, peak);
  }
  if (rises.empty() || afterWarmup == 0) return 0.0;
  std::sort(rises.begin(), rises.end());
  const size_t n = rises.size();
  const double quartile = double(rises[(n - 1) / 4]);
  return quartile * double(n) / double(afterWarmup);
}

// Bytes malloc has handed out and not had back (every arena, mmapped blocks
// included): what a leak grows even while glibc keeps freed memory resident
// (a small leak can fill free heap pages already counted in the resident size).
size_t heapInUseBytes() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

// Under AddressSanitizer the allocator is ASan's: freed blocks wait in its
// quarantine (up to 256 MiB) and shadow memory grows with use, so neither
// figure is the program's; LeakSanitizer checks for leaks at exit instead.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FACIAL_SOAK_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) && !defined(FACIAL_SOAK_UNDER_ASAN)
#define FACIAL_SOAK_UNDER_ASAN 1
#endif

struct SoakFigures {
  uint32_t frames = 0;
  uint32_t warmupFrames = 0;
  size_t residentAfterWarmup = 0;  // peak over the warm-up's second half
  size_t residentPeak = 0;  // after warm-up
  std::vector<size_t> windowPeaks = std::vector<size_t>(kWindows, 0);  // after warm-up
  size_t heapAfterWarmup = 0;      // likewise
  std::vector<size_t> heapWindowPeaks = std::vector<size_t>(kWindows, 0);
  size_t residentFinal = 0;
  uint32_t peakFrame = 0;
  uint32_t drawn = 0;
  uint64_t triggers = 0;
  uint64_t parameterChanges = 0;
  uint64_t resets = 0;
  uint64_t nonFiniteWeights = 0;
  double seconds = 0;
};

TEST(Soak, CrowdWithRandomTriggersKeepsMemoryFlatAndWeightsFinite) {
  const uint32_t frames = positiveEnv("FACIAL_SOAK_FRAMES", kShortRunFrames);
  const std::filesystem::path data = testing_support::sourceDir() / "data";

  auto model = eng::loadModel(data / "head.glb");
  ASSERT_TRUE(model.ok()) << model.error().message;
  const eng::WeightLayout layout(*model);
  const std::vector<std::string> targetNames = layout.names();
  auto rig = facial::buildRigMapping(targetNames);
  ASSERT_TRUE(rig.ok()) << rig.error().message;
  auto library = facial::ExpressionLibrary::load(data / "expressions.json");
  ASSERT_TRUE(library.ok()) << library.error().message;
  auto graph = facial::loadGraph(data / "graphs" / "tour.json", {facial::presetLookup(*library)});
  ASSERT_TRUE(graph.ok()) << graph.error().message;

  std::vector<facial::FaceDriver> faces;
  for (uint32_t i = 0; i < kCrowd; ++i) {
    auto face = facial::FaceDriver::create(*graph, &*rig, targetNames, layout.defaults(), /*seed=*/i);
    ASSERT_TRUE(face.ok()) << face.error().message;
    faces.push_back(std::move(*face));
  }

  eng::vk::ContextOptions contextOptions;
  contextOptions.applicationName = "test_soak";
  contextOptions.validation = true;
  uint32_t validationMessages = 0;
  std::string firstValidationMessage;
  contextOptions.onValidationMessage = [&](eng::LogLevel, std::string_view message) {
    if (validationMessages++ == 0) firstValidationMessage = message;
  };
  auto context = eng::vk::Context::create(contextOptions);
  ASSERT_TRUE(context.ok()) << context.error().message;
  auto renderer = eng::vk::OffscreenRenderer::create(*context, {.width = kImageSide, .height = kImageSide});
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  // Drawn as the programs draw it: the untextured head dressed for display.
  const std::optional<eng::Model> dressed = importers::dressedForDisplay(*model);
  auto gpuModel = renderer->upload(dressed ? *dressed : *model);
  ASSERT_TRUE(gpuModel.ok()) << gpuModel.error().message;

  // A 3x3 grid of heads, framed together.
  const eng::Aabb bounds = model->bounds();
  const float spacing = std::max(bounds.size().x, bounds.size().y) * 1.15f;
  eng::Aabb crowdBounds;
  std::vector<eng::vk::ModelInstance> instances(kCrowd);
  for (uint32_t i = 0; i < kCrowd; ++i) {
    const glm::vec3 offset((float(i % 3) - 1.0f) * spacing, (float(i / 3) - 1.0f) * spacing, 0.0f);
    crowdBounds.extend(bounds.min + offset);
    crowdBounds.extend(bounds.max + offset);
    instances[i].model = &*gpuModel;
    instances[i].transform = glm::translate(glm::mat4(1.0f), offset);
  }
  eng::vk::SceneView view{eng::OrbitCamera::frame(crowdBounds)};
  const bool cpuDevice = context->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const uint32_t drawEvery = positiveEnv("FACIAL_SOAK_DRAW_EVERY", cpuDevice ? 20 : 1);

  const facial::GraphDefinition& definition = **graph;
  static constexpr const char* kTriggers[] = {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"};
  std::vector<facial::ParameterIndex> triggers;
  for (const char* name : kTriggers) triggers.push_back(*definition.findParameter(name));
  const facial::ParameterIndex talk = *definition.findParameter("talk");
  const facial::ParameterIndex autoplay = *definition.findParameter("autoplay");

  std::mt19937 random(12);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> nextEvent(kCrowd, 0.0f);
  float time = 0.0f;

  SoakFigures figures;
  figures.frames = frames;
  figures.warmupFrames = std::max<uint32_t>(300, frames / 10);
  // A deliberate leak (bytes a frame, 0 by default): shows the checks below can fail.
  const size_t leakBytesPerFrame = positiveEnv("FACIAL_SOAK_LEAK_BYTES", 0);
  std::vector<std::unique_ptr<char[]>> leaked;
  const auto started = std::chrono::steady_clock::now();
  for (uint32_t frame = 0; frame < frames; ++frame) {
    if (leakBytesPerFrame) {
      leaked.push_back(std::make_unique<char[]>(leakBytesPerFrame));
      std::fill_n(leaked.back().get(), leakBytesPerFrame, char(frame));  // touched, so resident too
    }
    // Uneven frame times: 30-240 Hz, with a hitch now and then.
    float dt = 1.0f / (30.0f + 210.0f * unit(random));
    if (unit(random) < 0.002f) dt = 0.25f + unit(random);
    time += dt;
    for (uint32_t i = 0; i < kCrowd; ++i) {
      facial::GraphInstance& g = faces[i].graph();
      if (time >= nextEvent[i]) {
        const float pick = unit(random);
        if (pick < 0.7f) {
          g.setTrigger(triggers[std::uniform_int_distribution<size_t>(0, triggers.size() - 1)(random)]);
          ++figures.triggers;
        } else if (pick < 0.98f) {
          g.setFloat(talk, unit(random) < 0.5f ? 0.0f : unit(random));
          g.setBool(autoplay, unit(random) < 0.2f);
          figures.parameterChanges += 2;
        } else {
          g.reset();
          ++figures.resets;
        }
        // Mostly mid-transition: the next event often interrupts the blend.
        nextEvent[i] = time + 0.05f + 2.0f * unit(random);
      }
      ASSERT_TRUE(faces[i].update(dt));
      for (float w : faces[i].channelWeights()) figures.nonFiniteWeights += !std::isfinite(w);
      for (float w : faces[i].targetWeights()) figures.nonFiniteWeights += !std::isfinite(w);
      instances[i].weights = faces[i].targetWeights();
    }
    ASSERT_EQ(figures.nonFiniteWeights, 0u) << "frame " << frame << ": a weight is not finite";
    if (frame % drawEvery == 0 || frame + 1 == frames) {
      auto drawn = renderer->renderTimed(view, instances);
      ASSERT_TRUE(drawn.ok()) << "frame " << frame << ": " << drawn.error().message;
      ASSERT_EQ(validationMessages, 0u) << "frame " << frame << ": " << firstValidationMessage;
      ++figures.drawn;
    }

    // The baseline is the peak over the warm-up's second half, sampled as the
    // windows after it are: one sample taken at a trough (llvmpipe's
    // allocations come and go by several MiB) made an ordinary peak after it
    // count as growth.
    if (frame + 1 <= figures.warmupFrames && 2 * (frame + 1) >= figures.warmupFrames &&
        (frame % 25 == 0 || frame + 1 == figures.warmupFrames)) {
      figures.residentAfterWarmup = std::max(figures.residentAfterWarmup, residentBytes());
      figures.heapAfterWarmup = std::max(figures.heapAfterWarmup, heapInUseBytes());
    }
    if (frame + 1 > figures.warmupFrames && (frame % 25 == 0 || frame + 1 == frames)) {
      const size_t resident = residentBytes();
      const uint32_t window = uint32_t(uint64_t(frame + 1 - figures.warmupFrames) * kWindows /
                                       std::max<uint32_t>(1, frames - figures.warmupFrames + 1));
      size_t& windowPeak = figures.windowPeaks[std::min(window, kWindows - 1)];
      windowPeak = std::max(windowPeak, resident);
      size_t& heapPeak = figures.heapWindowPeaks[std::min(window, kWindows - 1)];
      heapPeak = std::max(heapPeak, heapInUseBytes());
      if (resident > figures.residentPeak) {
        figures.residentPeak = resident;
        figures.peakFrame = frame;
      }
    }
  }
  figures.residentFinal = residentBytes();
  figures.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  const double mib = 1.0 / (1 << 20);
  size_t largestRise = 0;
  const double growth = steadyGrowth(figures.residentAfterWarmup, figures.windowPeaks, largestRise);
  size_t largestHeapRise = 0;
  const double heapGrowth = steadyGrowth(figures.heapAfterWarmup, figures.heapWindowPeaks, largestHeapRise);
  std::string windows, heapWindows;
  for (size_t peak : figures.windowPeaks) windows += (windows.empty() ? "" : " ") + std::to_string(peak >> 20);
  for (size_t peak : figures.heapWindowPeaks)
    heapWindows += (heapWindows.empty() ? "" : " ") + std::to_string(peak >> 20);
  std::printf("soak: %u frames (%u warm-up, %u drawn) of %u faces at %ux%u in %.1f s (%.2f ms/frame); %llu triggers, "
              "%llu parameter changes, %llu resets\n"
              "soak: resident %.1f MiB after warm-up, peak %.1f MiB (frame %u), final %.1f MiB; window peaks (MiB) %s; "
              "largest rise %.1f MiB, steady growth +%.3f %%\n"
              "soak: heap in use %.1f MiB after warm-up; window peaks (MiB) %s; largest rise "
              "%.1f MiB, steady growth +%.3f %%; non-finite weights %llu; validation messages %u\n",
              figures.frames, figures.warmupFrames, figures.drawn, kCrowd, kImageSide, kImageSide, figures.seconds,
              1000.0 * figures.seconds / figures.frames, (unsigned long long)figures.triggers,
              (unsigned long long)figures.parameterChanges, (unsigned long long)figures.resets,
              figures.residentAfterWarmup * mib, figures.residentPeak * mib, figures.peakFrame,
              figures.residentFinal * mib, windows.c_str(), largestRise * mib, 100.0 * growth,
              figures.heapAfterWarmup * mib, heapWindows.c_str(), largestHeapRise * mib, 100.0 * heapGrowth,
              (unsigned long long)figures.nonFiniteWeights, validationMessages);
#ifdef FACIAL_SOAK_UNDER_ASAN
  std::printf("soak: AddressSanitizer build: memory figures are ASan's (quarantine, shadow), not checked; "
              "LeakSanitizer checks for leaks at exit\n");
#else
  EXPECT_LE(heapGrowth, kAllowedGrowth) << "heap in use kept growing after warm-up: from " << figures.heapAfterWarmup
                                        << " bytes, window peaks (MiB) " << heapWindows << " (steady growth: the lower-quartile rise between "
                                        << "windows, times their number)";
  EXPECT_LE(growth, kAllowedGrowth) << "resident memory kept growing after warm-up: from " << figures.residentAfterWarmup
                                    << " bytes, window peaks (MiB) " << windows << " (steady growth: the lower-quartile rise between "
                                    << "windows, times their number)";
#endif
  auto clean = context->checkValidation();
  EXPECT_TRUE(clean.ok()) << clean.error().message;
}

}  // namespace
