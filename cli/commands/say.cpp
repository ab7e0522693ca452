// `facial say "TEXT" [--lang CODE] [--emotion NAME] [--model M] [--rigmap R] [--size WxH] [--fps N] --out talk.mp4`
// `facial say --cues CUES.json|tsv --audio VOICE.ogg --out talk.mp4`
// `facial say --audio VOICE.ogg --out talk.mp4`
// A presenter: a face speaks a sentence (espeak-ng's voice and phoneme
// timings), a recording with Rhubarb cues, or a recording alone (the mouth
// follows the syllables), rendered headless into an MP4/WebM with the sound
// (audio::VideoWriter: written to .partial, renamed when complete).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/headless_model_renderer.h"
#include "app/program_error.h"
#include "app/sequence_recorder.h"
#include "app/view_options.h"
#include "audio/audio_file.h"
#include "audio/speech_synthesis.h"
#include "audio/syllable_envelope.h"
#include "audio/video_writer.h"
#include "cli/command.h"
#include "facial/character.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/speech/speech_timings.h"
#include "facial/runtime/speech/viseme_track.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit, where their file-local names would clash.
namespace cli::say_command {
namespace {

struct SayOptions {
  std::string text;
  std::string language = "en";
  std::string emotion = "neutral";
  std::string model;
  std::string rigmap;
  std::vector<std::string> shapes;
  // Balanced: high's 4x multisampling triples lavapipe's frame time (docs/performance.md, `say`).
  app::ViewOptions view{.quality = "balanced"};
  float fps = 25.0f;
  std::string cues;
  std::string audio;
  std::string out;
  std::string frames;
  std::string visemes;
};

constexpr app::ErrorReporter fail{"facial say"};

// The emotions of data/graphs/tour.json, each shading the synthesized voice a
// little (sad slower and lower, happy and surprise quicker and higher).
struct EmotionVoice {
  const char* name;
  float ratePercent;
  float pitchPercent;
};
constexpr EmotionVoice kEmotionVoices[] = {
    {"neutral", 100, 100}, {"happy", 108, 115}, {"sad", 85, 85},        {"anger", 105, 95},
    {"fear", 110, 120},    {"surprise", 110, 125}, {"disgust", 95, 90},
};

// The emotion settles before frame 0 (the graph's transitions take 0.8 s).
constexpr float kSettleSeconds = 1.5f;
constexpr float kSettleStep = 1.0f / 60.0f;
// The mouth after the last cue: a short tail so the video ends at rest.
constexpr float kTailSeconds = 0.2f;
// --visemes samples the track this often to write its dominant viseme.
constexpr float kVisemeSampleRate = 100.0f;

const EmotionVoice* emotionVoice(const std::string& name) {
  for (const EmotionVoice& e : kEmotionVoices)
    if (name == e.name) return &e;
  return nullptr;
}

std::string emotionList() {
  std::string list;
  for (const EmotionVoice& e : kEmotionVoices) list += (list.empty() ? "" : ", ") + std::string(e.name);
  return list;
}

// What the face says: the soundtrack and the viseme track that follows it.
struct Speech {
  std::vector<float> samples;
  int sampleRate = 0;
  std::shared_ptr<const facial::VisemeTrack> track;
  std::vector<std::string> warnings;
};

eng::Result<Speech> withTrack(Speech speech, eng::Result<facial::VisemeTrackBuild> built) {
  if (!built) return built.error();
  speech.track = std::make_shared<const facial::VisemeTrack>(std::move(built->track));
  speech.warnings = std::move(built->warnings);
  return speech;
}

eng::Result<Speech> synthesizedSpeech(const SayOptions& o, const EmotionVoice& voice) {
  if (std::all_of(o.text.begin(), o.text.end(), [](unsigned char c) { return std::isspace(c); }))
    return eng::Error{eng::ErrorKind::InvalidArgument, "TEXT is empty (give a sentence, or --audio FILE)"};
  auto spoken = audio::synthesize(o.text, {.language = o.language,
                                           .ratePercent = voice.ratePercent,
                                           .pitchPercent = voice.pitchPercent});
  if (!spoken) return spoken.error().prefixed("--lang '" + o.language + "': ");
  Speech speech;
  speech.sampleRate = spoken->sampleRate;
  speech.samples.reserve(spoken->samples.size());
  for (int16_t s : spoken->samples) speech.samples.push_back(float(s) / 32768.0f);
  std::vector<facial::TimedPhoneme> phonemes;
  for (const audio::TimedPhoneme& p : spoken->phonemes)
    phonemes.push_back({.ipa = p.ipa, .start = float(p.start), .end = float(p.end)});
  return withTrack(std::move(speech), facial::VisemeTrackBuilder{}.build(phonemes));
}

eng::Result<std::string> readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::Error{eng::ErrorKind::NotFound, path + ": cannot open file"};
  return std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Rhubarb's two outputs, told apart by the extension (.tsv/.txt) or, failing
// that, by the first character.
eng::Result<std::vector<facial::TimedViseme>> readCues(const std::string& path) {
  auto text = readText(path);
  if (!text) return text.error();
  const std::string ext = std::filesystem::path(path).extension().string();
  const size_t first = text->find_first_not_of(" \t\r\n");
  const bool json = ext == ".json" || (ext != ".tsv" && ext != ".txt" && first != std::string::npos &&
                                       ((*text)[first] == '{' || (*text)[first] == '['));
  return json ? facial::rhubarbFromJson(*text, path) : facial::rhubarbFromTsv(*text, path);
}

// Audio without text: each syllable's nucleus opens the mouth as wide as it
// is loud (aa wide, E half, nn a little), the consonants between nuclei keep
// it slightly open (DD), silence rests (sil). Visemes are all or nothing, so
// the openness is quantised into these three.
std::vector<facial::TimedViseme> visemesFromEnvelope(const audio::SyllableEnvelope& envelope) {
  std::vector<facial::TimedViseme> cues;
  for (const audio::MouthSegment& segment : envelope.segments) {
    if (segment.end <= segment.start) continue;
    facial::Viseme viseme = facial::Viseme::sil;
    if (segment.state == audio::MouthState::Open)
      viseme = segment.openness >= 0.5f ? facial::Viseme::aa
               : segment.openness >= 0.2f ? facial::Viseme::E
                                          : facial::Viseme::nn;
    else if (segment.state == audio::MouthState::Closed)
      viseme = facial::Viseme::DD;
    cues.push_back({.viseme = viseme, .start = float(segment.start), .end = float(segment.end)});
  }
  return cues;
}

eng::Result<Speech> recordedSpeech(const SayOptions& o) {
  auto clip = audio::readAudioFile(o.audio);
  if (!clip) return clip.error();
  Speech speech;
  speech.sampleRate = clip->sampleRate;
  speech.samples = std::move(clip->samples);
  if (!o.cues.empty()) {
    auto cues = readCues(o.cues);
    if (!cues) return cues.error();
    return withTrack(std::move(speech), facial::VisemeTrackBuilder{}.build(*cues));
  }
  auto envelope = audio::syllableEnvelope(speech.samples, speech.sampleRate, o.fps);
  if (!envelope) return envelope.error().prefixed(o.audio + ": ");
  const std::vector<facial::TimedViseme> cues = visemesFromEnvelope(*envelope);
  if (cues.empty()) return eng::Error{eng::ErrorKind::Malformed, o.audio + ": no sound to follow"};
  return withTrack(std::move(speech), facial::VisemeTrackBuilder{}.build(cues));
}

eng::Result<Speech> speechFor(const SayOptions& o, const EmotionVoice& voice) {
  constexpr auto invalid = eng::ErrorKind::InvalidArgument;
  if (!o.cues.empty() && o.audio.empty())
    return eng::Error{invalid, "--cues " + o.cues + " needs --audio FILE (the voice)"};
  if (!o.audio.empty() && !o.text.empty())
    return eng::Error{invalid, "give TEXT or --audio, not both (a transcript aligned to a recording is not supported)"};
  return o.audio.empty() ? synthesizedSpeech(o, voice) : recordedSpeech(o);
}

// The track as the project's timed-viseme JSON (visemesFromJson reads it): the
// dominant viseme sampled every 10 ms, equal neighbours merged.
eng::Result<void> writeVisemeJson(const facial::VisemeTrack& track, const std::string& path) {
  std::array<uint32_t, facial::kSpeechChannelCount> cursors{};
  std::array<float, facial::kVisemeCount> weights{};
  nlohmann::json cues = nlohmann::json::array();
  const auto steps = static_cast<uint32_t>(std::ceil(track.endTime() * kVisemeSampleRate));
  for (uint32_t i = 0; i < steps; ++i) {
    const float start = float(i) / kVisemeSampleRate;
    facial::VisemeSampleJob{.track = &track, .time = start + 0.5f / kVisemeSampleRate, .cursors = cursors,
                            .visemes = weights}
        .Run();
    const auto strongest = std::max_element(weights.begin(), weights.end());
    const auto dominant = static_cast<facial::Viseme>(strongest - weights.begin());
    const std::string name{facial::visemeName(dominant)};
    const float end = float(i + 1) / kVisemeSampleRate;
    if (!cues.empty() && cues.back()["viseme"] == name)
      cues.back()["end"] = end;
    else
      cues.push_back({{"viseme", name}, {"start", start}, {"end", end}});
  }
  std::ofstream out(path);
  out << nlohmann::json{{"version", facial::kSpeechTimingsVersion}, {"visemes", cues}}.dump(1) << "\n";
  if (!out) return eng::Error{eng::ErrorKind::Io, path + ": cannot write"};
  return {};
}

// The tour graph with autoplay off, so the emotion holds; the speaking character pre-rolled until it has settled.
eng::Result<facial::Character> emotionalCharacter(const app::FaceSetup& setup, const std::string& emotion) {
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
  if (auto triggered = character->trigger(emotion); !triggered) return triggered.error();
  for (float t = 0; t < kSettleSeconds; t += kSettleStep)
    if (auto stepped = character->update(kSettleStep); !stepped) return stepped.error();
  return character;
}

struct Presenter {
  app::FaceSetup setup;
  facial::Character character;
  app::FaceMaterials materials;
};

eng::Result<void> checkOptions(const SayOptions& o) {
  constexpr auto invalid = eng::ErrorKind::InvalidArgument;
  if (!std::isfinite(o.fps) || o.fps < 1.0f || o.fps > 240.0f)
    return eng::Error{invalid, "--fps must be a number in [1, 240], got " + std::to_string(o.fps)};
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext != ".mp4" && ext != ".webm")
    return eng::Error{invalid, "--out " + o.out + ": the video must end in .mp4 or .webm"};
  if (!emotionVoice(o.emotion))
    return eng::Error{invalid, "--emotion '" + o.emotion + "' is not one of " + emotionList()};
  return {};
}

// Renders the clip into the video (and the PNG frames), the audio clock driving the mouth.
eng::Result<app::SequenceSummary> renderClip(const SayOptions& o, Presenter& p, const Speech& speech,
                                             const app::HeadlessRenderOptions& renderOptions, float seconds) {
  auto renderer = app::HeadlessModelRenderer::create(p.setup.displayModel(), renderOptions);
  if (!renderer) return renderer.error();
  auto writer = audio::VideoWriter::create(o.out, {.width = int(renderOptions.width),
                                                   .height = int(renderOptions.height),
                                                   .framesPerSecond = o.fps,
                                                   .audioSamples = speech.samples,
                                                   .audioSampleRate = speech.sampleRate});
  if (!writer) return writer.error();
  if (!o.frames.empty()) std::filesystem::create_directories(o.frames);
  app::SequenceOptions sequence{.framesPerSecond = o.fps, .seconds = seconds, .frameDir = o.frames,
                                .progressLabel = "say"};
  eng::vk::ModelInstance instance{&renderer->gpuModel(), glm::mat4(1.0f), {}};
  eng::Result<void> written;  // the sink cannot fail the recording itself: the next step does
  auto summary = app::recordSequence(
      renderer->offscreen(), renderer->view(), sequence,
      [&](const app::FrameContext& frame) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        if (!written) return written.error();
        if (auto clock = p.character.setSpeechTime(frame.time); !clock) return clock.error();
        if (auto stepped = p.character.update(frame.index == 0 ? kSettleStep : frame.dt); !stepped)
          return stepped.error();
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
  if (auto clean = renderer->checkValidation(); !clean) return clean.error();
  if (auto finished = writer->finish(); !finished) return finished.error();
  return summary;
}

int runSay(const SayOptions& o) {
  if (auto checked = checkOptions(o); !checked) return fail(checked.error().message);
  auto renderOptions = app::headlessRenderOptions(o.view);
  if (!renderOptions) return fail(renderOptions.error().message);
  const EmotionVoice& voice = *emotionVoice(o.emotion);
  auto speech = speechFor(o, voice);
  if (!speech) return fail(speech.error().message);
  for (const std::string& warning : speech->warnings) std::fprintf(stderr, "facial say: note: %s\n", warning.c_str());

  auto setup = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes});
  if (!setup) return fail(setup.error().message);
  auto character = emotionalCharacter(*setup, o.emotion);
  if (!character) return fail(character.error().message);
  if (auto speaking = character->speak(speech->track); !speaking) return fail(speaking.error().message);
  auto materials = app::FaceMaterials::create(*setup);
  if (!materials) return fail(materials.error().message);
  Presenter presenter{std::move(*setup), std::move(*character), std::move(*materials)};

  const float audioSeconds = float(speech->samples.size()) / float(speech->sampleRate);
  const float seconds = std::max(audioSeconds, speech->track->endTime()) + kTailSeconds;
  if (!o.visemes.empty())
    if (auto json = writeVisemeJson(*speech->track, o.visemes); !json) return fail(json.error().message);
  auto summary = renderClip(o, presenter, *speech, *renderOptions, seconds);
  if (!summary) return fail(summary.error().message);
  std::printf("said %s on %s (%s): %u frames (%.2f s at %.0f fps) in %.1f s -> %s\n",
              o.audio.empty() ? ("\"" + o.text + "\"").c_str() : o.audio.c_str(), presenter.setup.name().c_str(),
              o.emotion.c_str(), summary->frames, seconds, o.fps, summary->totalSeconds, o.out.c_str());
  return 0;
}

CommandRegistrar reg("say", "A face speaks text (espeak-ng) or a recording, into an MP4/WebM with the sound",
                     [](CLI::App& app) {
  auto o = std::make_shared<SayOptions>();
  app.add_option("text", o->text, "The sentence to speak (omit with --audio)");
  app.add_option("--lang", o->language, "espeak-ng language or voice: en, fr, vi, en-us, ...")->capture_default_str();
  app.add_option("--emotion", o->emotion, "The face's emotion while it speaks: " + emotionList())
      ->capture_default_str();
  app::addFaceOptions(app, o->model, o->rigmap);
  app::addShapeOption(app, o->shapes);
  app::addViewOptions(app, o->view);
  app.add_option("--fps", o->fps, "Frames per second")->capture_default_str();
  app.add_option("--cues", o->cues, "Rhubarb Lip Sync cues (.json or .tsv) timing the mouth to --audio");
  app.add_option("--audio", o->audio, "A recording to speak (WAV, OGG, FLAC, MP3): with --cues, or alone");
  app.add_option("--out,-o", o->out, "The video: .mp4 (H.264 + AAC) or .webm (VP9 + Opus)")->required();
  app.add_option("--frames", o->frames, "Also write the frames as numbered PNGs into this folder");
  app.add_option("--visemes", o->visemes, "Also write the viseme track used, as timed-viseme JSON");
  return [o] { return runSay(*o); };
});

}  // namespace
}  // namespace cli::say_command
