// `facial say "TEXT" [--lang CODE] [--emotion NAME] [--intensity X] [--model M] [--rigmap R] [--size WxH] [--fps N] --out talk.mp4`
// `facial say --script bulletin.txt --out news.mp4`
// `facial say --cues CUES.json|tsv --audio VOICE.ogg --out talk.mp4`
// `facial say --audio VOICE.wav [--text "..."] --out talk.mp4`
// A presenter: a face speaks a sentence or a whole bulletin (espeak-ng's
// voice and phoneme timings), a recording with Rhubarb cues or its transcript,
// or a recording alone, rendered headless into an MP4/WebM with the sound.
// The halves: cli/say_speech.cpp (what is said), cli/say_render.cpp (the video).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/output_paths.h"
#include "app/program_error.h"
#include "audio/audio_file.h"
#include "cli/command.h"
#include "cli/say.h"
#include "facial/runtime/rig/emotions.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit, where their file-local names would clash.
namespace cli::say_command {
namespace {

using say::SayOptions;

constexpr app::ErrorReporter fail{"facial say"};

// The mouth after the last cue: a short tail so the video ends at rest.
constexpr float kTailSeconds = 0.2f;

eng::Result<void> checkOptions(const SayOptions& o) {
  constexpr auto invalid = eng::ErrorKind::InvalidArgument;
  if (!std::isfinite(o.lodError) || o.lodError < 0.0f || o.lodError > 64.0f)
    return eng::Error{invalid, "--lod-error must be a number of pixels in [0, 64], got " + std::to_string(o.lodError)};
  if (!std::isfinite(o.fps) || o.fps < 1.0f || o.fps > 240.0f)
    return eng::Error{invalid, "--fps must be a number in [1, 240], got " + std::to_string(o.fps)};
  if (!(o.intensity >= 0.0f && o.intensity <= 1.0f))  // NaN fails too
    return eng::Error{invalid, "--intensity must be a number in [0, 1], got " + std::to_string(o.intensity)};
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext != ".mp4" && ext != ".webm")
    return eng::Error{invalid, "--out " + o.out + ": the video must end in .mp4 or .webm"};
  if (!o.wav.empty() && std::filesystem::path(o.wav).extension() != ".wav")
    return eng::Error{invalid, "--wav " + o.wav + ": the soundtrack file must end in .wav"};
  ENG_TRY(app::checkOutputs({.inputs = {{"--script", o.script}, {"--cues", o.cues}, {"--audio", o.audio},
                                        {"--model", o.model}, {"--rigmap", o.rigmap}},
                             .outputs = {{"--out", o.out}, {"--wav", o.wav}, {"--visemes", o.visemes}},
                             .frameFolders = {{"--frames", o.frames}}}));
  if (!facial::emotionIndex(o.emotion))
    return eng::Error{invalid, "--emotion '" + o.emotion + "' is not one of " + facial::emotionNameList()};
  return {};
}

// "happy", or "happy > sad > neutral" for a bulletin.
std::string emotionsShown(const say::Speech& speech) {
  std::string shown;
  for (const say::EmotionCue& cue : speech.emotions) shown += (shown.empty() ? "" : " > ") + cue.emotion;
  return shown;
}

std::string whatWasSaid(const SayOptions& o) {
  if (!o.script.empty()) return o.script;
  return o.audio.empty() ? "\"" + o.text + "\"" : o.audio;
}

int runSay(const SayOptions& o) {
  if (auto checked = checkOptions(o); !checked) return fail(checked.error().message);
  auto renderOptions = app::headlessRenderOptions(o.view);
  if (!renderOptions) return fail(renderOptions.error().message);
  // Pixels of a 512-pixel-tall frame: a smaller one draws no coarser a level (at 256 px, half a
  // pixel is a level that loses lip shapes only targets make; docs/performance.md).
  renderOptions->lodPixelError = o.lodError * std::min(1.0f, float(renderOptions->height) / 512.0f);
  renderOptions->framesInFlight = app::kSequenceFramesInFlight;
  // The devices and their pipelines open on threads while the voice is synthesised and the face loaded.
  app::SequenceRenderers::Opening renderers = app::SequenceRenderers::open(*renderOptions);
  auto speech = say::speechFor(o);
  if (!speech) return fail(speech.error().message);
  for (const std::string& note : speech->notes) std::fprintf(stderr, "facial say: note: %s\n", note.c_str());

  auto presenter = say::makePresenter(o, *speech);
  if (!presenter) return fail(presenter.error().message);
  const float seconds = std::max(speech->seconds(), speech->track->endTime()) + kTailSeconds;
  // The soundtrack (and --wav) runs as long as the video's whole frames (recordSequence's
  // count): the two streams end together.
  const double videoSeconds = std::ceil(double(seconds) * o.fps) / o.fps;
  speech->samples.resize(size_t(std::ceil(videoSeconds * speech->sampleRate)), 0.0f);
  if (!o.visemes.empty())
    if (auto json = say::writeVisemeJson(*speech->track, o.visemes); !json) return fail(json.error().message);
  auto summary = say::renderClip(o, *presenter, *speech, renderers, seconds);
  if (!summary) return fail(summary.error().message);
  if (!o.wav.empty())
    if (auto wav = audio::writeWavFile(o.wav, speech->samples, speech->sampleRate); !wav)
      return fail(wav.error().message);
  std::printf("said %s on %s (%s): %u frames (%.2f s at %.0f fps) in %.1f s -> %s\n", whatWasSaid(o).c_str(),
              presenter->setup.name().c_str(), emotionsShown(*speech).c_str(), summary->frames, seconds, o.fps,
              summary->totalSeconds, o.out.c_str());
  return 0;
}

CommandRegistrar reg("say", "A face speaks text, a presenter script or a recording, into an MP4/WebM with the sound",
                     [](CLI::App& app) {
  auto o = std::make_shared<SayOptions>();
  app.add_option("text", o->text, "The sentence to speak (omit with --audio or --script)");
  app.add_option("--text", o->text, "With --audio: its transcript (English), force-aligned to time the mouth");
  app.add_option("--script", o->script, "A presenter script: lines, [emotion X] and [pause S] tags (docs/speech.md)");
  app.add_option("--lang", o->language, "espeak-ng language or voice: en, fr, vi, en-us, ...")->capture_default_str();
  app.add_option("--emotion", o->emotion, "The face's emotion while it speaks: " + facial::emotionNameList())
      ->capture_default_str();
  app.add_option("--intensity,-i", o->intensity, "How strongly the emotion shows, 0..1")->capture_default_str();
  app::addFaceOptions(app, o->model, o->rigmap, o->noAutorig);
  app::addShapeOption(app, o->shapes);
  app::addViewOptions(app, o->view);
  app.add_option("--fps", o->fps, "Frames per second")->capture_default_str();
  app.add_option("--lod-error", o->lodError,
                 "Level of detail: each mesh at the coarsest level within this many pixels of the full one, counted "
                 "at 512 px tall (a smaller frame draws the same level; 0: every triangle)")
      ->capture_default_str();
  app.add_option("--cues", o->cues, "Rhubarb Lip Sync cues (.json or .tsv) timing the mouth to --audio");
  app.add_option("--audio", o->audio, "A recording to speak (WAV, OGG, FLAC, MP3): with --cues, --text, or alone");
  app.add_option("--out,-o", o->out, "The video: .mp4 (H.264 + AAC) or .webm (VP9 + Opus)")->required();
  app.add_option("--wav", o->wav, "Also write the soundtrack as a WAV file");
  app.add_option("--frames", o->frames, "Also write the frames as numbered PNGs into this folder");
  app.add_flag("--profile", o->profile, "Print where each frame's time went (mean ms and share per stage)");
  app.add_option("--visemes", o->visemes, "Also write the viseme track used, as timed-viseme JSON");
  return [o] { return runSay(*o); };
});

}  // namespace
}  // namespace cli::say_command
