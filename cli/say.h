#pragma once
// `facial say` (cli/commands/say.cpp) in two halves: what the face says
// (say_speech.cpp: synthesis, recordings, cues, alignment, presenter scripts
// -> one soundtrack, one viseme track, the emotion changes on its clock) and
// how it is rendered (say_render.cpp: the speaking character, the emotion
// changes played on it, the video with its sound).
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/headless_model_renderer.h"
#include "app/sequence_recorder.h"
#include "app/sequence_renderers.h"
#include "app/view_options.h"
#include "engine/core/result.h"
#include "facial/character.h"
#include "facial/runtime/speech/viseme_track.h"

namespace cli::say {

struct SayOptions {
  std::string text;
  std::string language = "en";
  std::string emotion = "neutral";
  float intensity = 1.0f;
  std::string model;
  std::string rigmap;
  bool noAutorig = false;
  std::vector<std::string> shapes;
  // Balanced: high's 4x multisampling triples lavapipe's frame time (docs/performance.md, `say`).
  app::ViewOptions view{.quality = app::kQualityAuto};  // balanced on lavapipe, high on a GPU
  float fps = 25.0f;
  // Each mesh at the coarsest level of detail within this many pixels of the
  // full one, counted at 512 px tall (0: every triangle). A CPU rasteriser shades whole blocks per
  // triangle, and a head of 80k triangles at 512x512 has about one a pixel:
  // half a pixel takes the built-in head to 38k and its frame from 83 to
  // 54 ms on lavapipe; levels keep painted lines and creases whole
  // (eng::keptTriangles), so the picture differs on a few dozen pixels.
  float lodError = 0.5f;
  std::string cues;
  std::string audio;
  std::string script;
  std::string out;
  std::string wav;
  std::string frames;
  std::string visemes;
  bool profile = false;  // print where each frame's time went
};

// From `time` on the soundtrack the face shows `emotion` at `intensity`.
struct EmotionCue {
  float time = 0.0f;
  std::string emotion;
  float intensity = 1.0f;
};

// What the face says: the soundtrack, the viseme track that follows it and
// the emotions along it (the first at 0).
struct Speech {
  std::vector<float> samples;
  int sampleRate = 0;
  std::shared_ptr<const facial::VisemeTrack> track;
  std::vector<std::string> notes;  // printed as "facial say: note: ..."
  std::vector<EmotionCue> emotions;
  float seconds() const { return sampleRate > 0 ? float(samples.size()) / float(sampleRate) : 0.0f; }
};

// Text, a recording (with cues, a transcript or alone) or a presenter script,
// as the options say; errors are one line naming the argument or file.
eng::Result<Speech> speechFor(const SayOptions& o);

// The track as the project's timed-viseme JSON (visemesFromJson reads it).
eng::Result<void> writeVisemeJson(const facial::VisemeTrack& track, const std::string& path);

struct Presenter {
  app::FaceSetup setup;
  facial::Character character;
  app::FaceMaterials materials;
};

// The face speaking `speech`, its first emotion settled before frame 0.
eng::Result<Presenter> makePresenter(const SayOptions& o, const Speech& speech);

// Renders the clip into the video (and the PNG frames), the audio clock
// driving the mouth and the emotion changes, on renderers opened (with
// app::kSequenceFramesInFlight) while the face was loaded.
eng::Result<app::SequenceSummary> renderClip(const SayOptions& o, Presenter& p, const Speech& speech,
                                             app::SequenceRenderers::Opening& renderers, float seconds);

}  // namespace cli::say
