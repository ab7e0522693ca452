#include "app/sequence_recorder.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>

#include "app/gif_writer.h"
#include "app/output_paths.h"
#include "app/progress_bar.h"
#include "app/stage_profile.h"
#include "engine/scene/image_io.h"

namespace app {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

enum Stage : size_t { kStep, kSubmit, kWait, kReadback, kPng, kGif, kSink, kGpuShadow, kGpuView };
StageProfile makeProfile() {
  return StageProfile({"step (graph, speech, materials)", "submit (upload, record)", "wait for the GPU",
                       "read-back", "PNG encoding", "GIF encoding", "sink (video encoder queue, sheet)",
                       "GPU: morph + shadow map", "GPU: 3D view + resolve + copy"});
}

// Where a collected frame goes: the PNG folder, the GIF, the caller's sink.
struct Outputs {
  std::optional<FrameFolder> frames;
  std::optional<GifWriter> gif;
  const FrameSink* sink = nullptr;

  eng::Result<void> write(const FrameContext& frame, const eng::Image& image, StageProfile& profile) {
    Clock::time_point start = Clock::now();
    if (frames) {
      ENG_TRY(eng::writePng(frames->framePath(frame.index), image.width, image.height, image.rgba8));
      profile.add(kPng, msSince(start));
    }
    start = Clock::now();
    if (gif) {
      ENG_TRY(gif->addFrame(image.rgba8));
      profile.add(kGif, msSince(start));
    }
    start = Clock::now();
    if (*sink) {
      (*sink)(frame, image);
      profile.add(kSink, msSince(start));
    }
    return {};
  }
};

eng::Result<Outputs> openOutputs(const eng::vk::OffscreenRenderer& renderer, const SequenceOptions& options,
                                 const FrameSink& sink) {
  Outputs out;
  out.sink = &sink;
  if (!options.frameDir.empty()) out.frames.emplace(ENG_TRY_VALUE(FrameFolder::create(options.frameDir)));
  if (!options.gifPath.empty()) {
    const VkExtent2D extent = renderer.extent();
    out.gif.emplace(ENG_TRY_VALUE(GifWriter::create(options.gifPath, static_cast<int>(extent.width),
                                                    static_cast<int>(extent.height), options.framesPerSecond)));
  }
  return out;
}

// The oldest frame in flight, read back from its lane and written out.
eng::Result<void> finishOldest(std::span<const SequenceLane> lanes, std::deque<FrameContext>& inFlight,
                               Outputs& out, StageProfile& profile, SequenceSummary& summary) {
  const FrameContext frame = inFlight.front();
  inFlight.pop_front();
  eng::vk::OffscreenRenderer& renderer = *lanes[frame.lane].renderer;
  const Clock::time_point start = Clock::now();
  auto image = renderer.collect();
  if (!image) return image.error().prefixed("frame " + std::to_string(frame.index) + ": ");
  summary.renderSeconds += msSince(start) * 1e-3;
  const eng::vk::OffscreenFrameTimes& times = renderer.lastFrameTimes();
  profile.add(kWait, times.waitMs);
  profile.add(kReadback, times.readbackMs);
  if (times.gpuShadowMs) profile.add(kGpuShadow, *times.gpuShadowMs);
  if (times.gpuViewMs) profile.add(kGpuView, *times.gpuViewMs);
  ENG_TRY(out.write(frame, *image, profile));
  profile.endFrame();
  summary.frames = frame.index + 1;
  return {};
}

// Drops the frames still in flight when a sequence ends early.
struct DiscardOnExit {
  std::span<const SequenceLane> lanes;
  ~DiscardOnExit() {
    for (const SequenceLane& lane : lanes) lane.renderer->discardPending();
  }
};

}  // namespace

eng::Result<SequenceSummary> recordSequence(eng::vk::OffscreenRenderer& renderer, const eng::vk::SceneView& view,
                                            const SequenceOptions& options, const FrameStep& step,
                                            const FrameSink& sink) {
  const SequenceLane lane{&renderer, &view};
  return recordSequence({&lane, 1}, options, step, sink);
}

eng::Result<SequenceSummary> recordSequence(std::span<const SequenceLane> lanes, const SequenceOptions& options,
                                            const FrameStep& step, const FrameSink& sink) {
  if (lanes.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "a sequence needs a renderer");
  for (const SequenceLane& lane : lanes) {
    const VkExtent2D extent = lane.renderer->extent(), first = lanes.front().renderer->extent();
    if (extent.width != first.width || extent.height != first.height)
      return eng::makeError(eng::ErrorKind::InvalidArgument,
                            "a sequence's renderers draw " + std::to_string(first.width) + "x" +
                                std::to_string(first.height) + " and " + std::to_string(extent.width) + "x" +
                                std::to_string(extent.height) + ": one size for every frame");
  }
  if (!(options.framesPerSecond > 0.0f) || !std::isfinite(options.framesPerSecond) || options.framesPerSecond > 240)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "frame rate must be in (0, 240] fps");
  if (!(options.seconds > 0.0f) || !std::isfinite(options.seconds) || options.seconds > 3600)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "duration must be in (0, 3600] seconds");
  const uint32_t frameCount = static_cast<uint32_t>(std::ceil(options.seconds * options.framesPerSecond));
  const float dt = 1.0f / options.framesPerSecond;
  Outputs out = ENG_TRY_VALUE(openOutputs(*lanes.front().renderer, options, sink));

  const Clock::time_point start = Clock::now();
  SequenceSummary summary;
  StageProfile profile = makeProfile();
  ProgressBar progress(options.progressLabel, frameCount);
  DiscardOnExit discard{lanes};
  for (const SequenceLane& lane : lanes) lane.renderer->timeGpuPasses(options.profile);
  std::deque<FrameContext> inFlight;
  for (uint32_t i = 0; i < frameCount; ++i) {
    const uint32_t laneIndex = i % static_cast<uint32_t>(lanes.size());
    eng::vk::OffscreenRenderer& renderer = *lanes[laneIndex].renderer;
    // In order: the lane's own oldest frames come back first.
    while (renderer.pendingFrames() == renderer.framesInFlight())
      ENG_TRY(finishOldest(lanes, inFlight, out, profile, summary));
    const FrameContext frame{i, static_cast<float>(i) * dt, i == 0 ? 0.0f : dt, laneIndex};
    Clock::time_point stageStart = Clock::now();
    auto instances = step(frame);
    if (!instances) return instances.error();
    profile.add(kStep, msSince(stageStart));
    stageStart = Clock::now();
    if (auto submitted = renderer.submit(*lanes[laneIndex].view, *instances); !submitted)
      return submitted.error().prefixed("frame " + std::to_string(i) + ": ");
    const double submitMs = msSince(stageStart);
    profile.add(kSubmit, submitMs);
    summary.renderSeconds += submitMs * 1e-3;
    inFlight.push_back(frame);
    progress.update(i + 1);
  }
  while (!inFlight.empty()) ENG_TRY(finishOldest(lanes, inFlight, out, profile, summary));
  progress.finish();
  if (out.gif) ENG_TRY(out.gif->finish());
  if (out.frames) ENG_TRY(out.frames->commit());
  summary.totalSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (options.profile) profile.print(options.progressLabel, summary.totalSeconds);
  return summary;
}

}  // namespace app
