// How `facial say` renders: the tour graph's character speaking over its
// emotion, the emotion changes played on it at their times, and the frames
// encoded with the soundtrack (audio::VideoWriter: written to .partial,
// renamed when complete).
#include <algorithm>
#include <filesystem>

#include "audio/video_writer.h"
#include "cli/say.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace cli::say {
namespace {

// The first emotion settles before frame 0 (the graph's transitions take 0.8 s).
constexpr float kSettleSeconds = 1.5f;
constexpr float kSettleStep = 1.0f / 60.0f;
// The tour graph's anyState transitions last 0.6 s: a change of intensity
// glides over the same time, so the outgoing emotion fades and never jumps.
constexpr float kIntensityGlideSeconds = 0.6f;
// The tour graph's float parameter scaling every emotion's pose.
constexpr const char* kIntensityParameter = "intensity";

// Plays the emotion cues on the character as the audio clock passes them:
// a new emotion through the graph's trigger (the state machine blends it in,
// mid-sentence too), a new intensity through its parameter.
class EmotionPlayer {
 public:
  // The first cue is shown already (emotionalCharacter).
  explicit EmotionPlayer(std::span<const EmotionCue> cues)
      : cues_(cues), from_(cues.front().intensity), to_(cues.front().intensity) {}

  eng::Result<void> advance(facial::Character& c, float time) {
    for (; next_ < cues_.size() && cues_[next_].time <= time; ++next_) {
      from_ = intensityAt(time);
      to_ = cues_[next_].intensity;
      since_ = cues_[next_].time;
      if (cues_[next_].emotion != cues_[next_ - 1].emotion) ENG_TRY(c.trigger(cues_[next_].emotion));
    }
    return c.setFloat(kIntensityParameter, intensityAt(time));
  }

 private:
  float intensityAt(float time) const {
    const float t = std::clamp((time - since_) / kIntensityGlideSeconds, 0.0f, 1.0f);
    return from_ + (to_ - from_) * t;
  }

  std::span<const EmotionCue> cues_;
  size_t next_ = 1;
  float from_, to_, since_ = 0.0f;
};

// The tour graph with autoplay off, so the emotion holds; the speaking
// character showing the first emotion, pre-rolled until it has settled.
eng::Result<facial::Character> emotionalCharacter(const app::FaceSetup& setup, const EmotionCue& first) {
  const std::filesystem::path graphPath = app::dataDirectory() / "graphs" / "tour.json";
  facial::GraphLoadOptions graphOptions;
  graphOptions.presets = facial::presetLookup(setup.expressions());
  auto graph = facial::loadGraph(graphPath, graphOptions);
  if (!graph) return graph.error();
  const std::vector<std::string> targetNames = setup.layout().names();
  const facial::CharacterParts parts{.graph = *graph, .rig = &setup.graphRig(), .restWeights = setup.baseWeights(),
                                     .vrm = setup.vrm()};
  auto character = facial::Character::create(parts, targetNames, {.speaks = true});
  if (!character) return character.error().prefixed(setup.name() + ": ");
  if (auto off = character->setBool("autoplay", false); !off) return off.error();
  if (auto scaled = character->setFloat(kIntensityParameter, first.intensity); !scaled) return scaled.error();
  if (auto triggered = character->trigger(first.emotion); !triggered) return triggered.error();
  for (float t = 0; t < kSettleSeconds; t += kSettleStep)
    if (auto stepped = character->update(kSettleStep); !stepped) return stepped.error();
  return character;
}

}  // namespace

eng::Result<Presenter> makePresenter(const SayOptions& o, const Speech& speech) {
  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial say"});
  if (!setup) return setup.error();
  auto character = emotionalCharacter(*setup, speech.emotions.front());
  if (!character) return character.error();
  if (auto speaking = character->speak(speech.track); !speaking) return speaking.error();
  auto materials = app::FaceMaterials::create(*setup);
  if (!materials) return materials.error();
  return Presenter{std::move(*setup), std::move(*character), std::move(*materials)};
}

eng::Result<app::SequenceSummary> renderClip(const SayOptions& o, Presenter& p, const Speech& speech,
                                             app::SequenceRenderers::Opening& opening, float seconds) {
  auto renderers = opening.finish(p.setup.displayModel());
  if (!renderers) return renderers.error();
  const VkExtent2D size = renderers->lanes().front().renderer->extent();
  auto writer = audio::VideoWriter::create(o.out, {.width = int(size.width),
                                                   .height = int(size.height),
                                                   .framesPerSecond = o.fps,
                                                   .audioSamples = speech.samples,
                                                   .audioSampleRate = speech.sampleRate});
  if (!writer) return writer.error();
  if (!o.frames.empty()) std::filesystem::create_directories(o.frames);
  app::SequenceOptions sequence{.framesPerSecond = o.fps, .seconds = seconds, .frameDir = o.frames,
                                .progressLabel = "say", .profile = o.profile};
  EmotionPlayer emotions(speech.emotions);
  eng::vk::ModelInstance instance{&renderers->gpuModel(0), glm::mat4(1.0f), {}};
  eng::Result<void> written;  // the sink cannot fail the recording itself: the next step does
  auto summary = app::recordSequence(
      renderers->lanes(), sequence,
      [&](const app::FrameContext& frame) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        if (!written) return written.error();
        // A frame stands for the sound of its whole interval: the mouth at its middle
        // (at the start it trailed the sound by 0.7 frame, tests/cli/say_sync_test.cpp).
        const float heard = frame.time + 0.5f / o.fps;
        if (auto clock = p.character.setSpeechTime(heard); !clock) return clock.error();
        if (auto moved = emotions.advance(p.character, frame.time); !moved) return moved.error();
        if (auto stepped = p.character.update(frame.index == 0 ? kSettleStep : frame.dt); !stepped)
          return stepped.error();
        instance.model = &renderers->gpuModel(frame.lane);
        instance.weights = p.character.weights();
        if (auto moved = p.materials.update(p.character.expressionWeights()); !moved) return moved.error();
        instance.materials = p.materials.materials();
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      },
      [&](const app::FrameContext&, const eng::Image& image) {
        if (written) written = writer->addFrame(image.rgba8);
      });
  if (!summary) return summary.error();
  if (!written) return written.error();
  if (auto clean = renderers->checkValidation(); !clean) return clean.error();
  if (auto finished = writer->finish(); !finished) return finished.error();
  return summary;
}

}  // namespace cli::say
