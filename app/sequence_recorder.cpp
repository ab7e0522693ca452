#include "app/sequence_recorder.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/progress_bar.h"
#include "app/gif_writer.h"
#include "app/output_paths.h"
#include "engine/scene/image_io.h"

namespace app {

eng::Result<SequenceSummary> recordSequence(eng::vk::OffscreenRenderer& renderer, const eng::vk::SceneView& view,
                                            const SequenceOptions& options, const FrameStep& step,
                                            const FrameSink& sink) {
  if (!(options.framesPerSecond > 0.0f) || !std::isfinite(options.framesPerSecond) || options.framesPerSecond > 240)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "frame rate must be in (0, 240] fps");
  if (!(options.seconds > 0.0f) || !std::isfinite(options.seconds) || options.seconds > 3600)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "duration must be in (0, 3600] seconds");
  const uint32_t frameCount = static_cast<uint32_t>(std::ceil(options.seconds * options.framesPerSecond));
  const float dt = 1.0f / options.framesPerSecond;

  std::optional<FrameFolder> frames;
  if (!options.frameDir.empty()) frames.emplace(ENG_TRY_VALUE(FrameFolder::create(options.frameDir)));
  std::optional<app::GifWriter> gif;
  if (!options.gifPath.empty()) {
    const VkExtent2D extent = renderer.extent();
    auto created = app::GifWriter::create(options.gifPath, static_cast<int>(extent.width),
                                          static_cast<int>(extent.height), options.framesPerSecond);
    if (!created) return created.error();
    gif.emplace(std::move(*created));
  }

  const auto start = std::chrono::steady_clock::now();
  SequenceSummary summary;
  ProgressBar progress(options.progressLabel, frameCount);
  for (uint32_t i = 0; i < frameCount; ++i) {
    const FrameContext frame{i, static_cast<float>(i) * dt, i == 0 ? 0.0f : dt};
    auto instances = step(frame);
    if (!instances) return instances.error();
    const auto renderStart = std::chrono::steady_clock::now();
    auto image = renderer.render(view, *instances);
    if (!image) return image.error().prefixed("frame " + std::to_string(i) + ": ");
    summary.renderSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - renderStart).count();
    if (frames) {
      if (auto written = eng::writePng(frames->framePath(i), image->width, image->height, image->rgba8); !written)
        return written.error();
    }
    if (gif) {
      if (auto added = gif->addFrame(image->rgba8); !added) return added.error();
    }
    if (sink) sink(frame, *image);
    summary.frames = i + 1;
    progress.update(i + 1);
  }
  progress.finish();
  if (gif) {
    if (auto finished = gif->finish(); !finished) return finished.error();
  }
  if (frames) ENG_TRY(frames->commit());
  summary.totalSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace app
