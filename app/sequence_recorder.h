#pragma once
// Headless playback: steps animated faces at a fixed frame rate, renders each
// frame offscreen and writes numbered PNGs, optionally an animated GIF, and
// keeps chosen frames for a contact sheet. Shared by `facial play` and the
// demo's headless tour.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "engine/image/canvas.h"
#include "engine/vk/draw/offscreen_renderer.h"
#include "engine/vk/draw/scene_view.h"

namespace app {

// The renderer's frames in flight a sequence wants (HeadlessRenderOptions::
// framesInFlight): one read back and encoded, one rendering, one queued.
constexpr uint32_t kSequenceFramesInFlight = 3;

struct SequenceOptions {
  float framesPerSecond = 24.0f;
  float seconds = 10.0f;
  std::filesystem::path frameDir;    // frame_0000.png ..., written whole (app::FrameFolder); empty: no PNGs
  std::filesystem::path gifPath;     // empty: no GIF
  std::string progressLabel = "rendering";
  // Print where each frame's time went at the end (app::StageProfile).
  bool profile = false;
};

// Called before frame `index` is rendered at time `time` (seconds): advance
// the animation by dt and fill the instances to draw. Returns false to stop
// with an error message in `error`.
struct FrameContext {
  uint32_t index = 0;
  float time = 0;
  float dt = 0;
  uint32_t lane = 0;  // which SequenceLane renders the frame: its instances must be that lane's GpuModels
};
using FrameStep = std::function<eng::Result<std::span<const eng::vk::ModelInstance>>(const FrameContext&)>;
// Called after a frame was rendered, with its pixels (e.g. to keep it for a
// contact sheet), in frame order. With frames in flight it comes after the
// next frames' steps (the renderer copied their data when they were submitted).
using FrameSink = std::function<void(const FrameContext&, const eng::Image&)>;

struct SequenceSummary {
  uint32_t frames = 0;
  double renderSeconds = 0;   // submitting and waiting for the frames, summed
  double totalSeconds = 0;    // wall time incl. encoding
};

// One renderer of a sequence and the camera it draws with. Several lanes (each
// its own device) take frames in turn: on a CPU rasteriser one device's serial
// vertex and binning work then overlaps another's rasterising.
struct SequenceLane {
  eng::vk::OffscreenRenderer* renderer = nullptr;
  const eng::vk::SceneView* view = nullptr;
};

// Frames go through the renderer's frames in flight (OffscreenOptions::
// framesInFlight): frame N is read back and encoded while the device renders
// N+1. On an error the frames in flight are dropped and nothing is committed
// (the PNG folder and the GIF are written whole or not at all).
eng::Result<SequenceSummary> recordSequence(eng::vk::OffscreenRenderer& renderer, const eng::vk::SceneView& view,
                                            const SequenceOptions& options, const FrameStep& step,
                                            const FrameSink& sink = {});
// The same over several lanes: frame i goes to lane i % lanes.size(); the sink
// still gets the frames in order.
eng::Result<SequenceSummary> recordSequence(std::span<const SequenceLane> lanes, const SequenceOptions& options,
                                            const FrameStep& step, const FrameSink& sink = {});

}  // namespace app
