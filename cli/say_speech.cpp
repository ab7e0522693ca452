// What `facial say` speaks: espeak-ng's voice and phoneme timings for text or
// a presenter script, a recording with Rhubarb cues, with its transcript
// (force-aligned) or alone (the mouth follows the syllables).
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "app/presenter_script.h"
#include "audio/audio_file.h"
#include "audio/speech_synthesis.h"
#include "audio/spoken_line.h"
#include "audio/syllable_envelope.h"
#include "audio/transcript_alignment.h"
#include "cli/say.h"
#include "facial/runtime/speech/speech_timings.h"

namespace cli::say {
namespace {

// --visemes samples the track this often to write its dominant viseme.
constexpr float kVisemeSampleRate = 100.0f;

constexpr auto kInvalid = eng::ErrorKind::InvalidArgument;

// The track built from timed phonemes or visemes; the phonemes it could not map become notes.
template <class Timed>
eng::Result<Speech> withTrack(Speech speech, const std::vector<Timed>& timed) {
  auto built = facial::VisemeTrackBuilder{}.build(timed);
  if (!built) return built.error();
  speech.track = std::make_shared<const facial::VisemeTrack>(std::move(built->track));
  speech.notes.insert(speech.notes.end(), built->warnings.begin(), built->warnings.end());
  return speech;
}

// Appends `text` spoken in the emotion's voice (its shading scaled by the
// intensity) to the soundtrack, its phonemes shifted to where it starts.
eng::Result<void> speakInto(Speech& speech, std::vector<facial::TimedPhoneme>& phonemes, const std::string& text,
                            const std::string& language, const EmotionCue& emotion) {
  auto spoken = audio::synthesize(text, audio::emotionalVoice(language, emotion.emotion, emotion.intensity));
  if (!spoken) return spoken.error().prefixed("--lang '" + language + "': ");
  if (speech.sampleRate == 0) speech.sampleRate = spoken->sampleRate;
  const float offset = speech.seconds();
  for (int16_t s : spoken->samples) speech.samples.push_back(float(s) / 32768.0f);
  audio::appendTrackPhonemes(spoken->phonemes, offset, phonemes);
  return {};
}

eng::Result<Speech> synthesizedSpeech(const SayOptions& o) {
  if (std::all_of(o.text.begin(), o.text.end(), [](unsigned char c) { return std::isspace(c); }))
    return eng::Error{kInvalid, "TEXT is empty (give a sentence, --audio FILE or --script FILE)"};
  Speech speech;
  speech.emotions = {{.time = 0.0f, .emotion = o.emotion, .intensity = o.intensity}};
  std::vector<facial::TimedPhoneme> phonemes;
  ENG_TRY(speakInto(speech, phonemes, o.text, o.language, speech.emotions.front()));
  return withTrack(std::move(speech), phonemes);
}

// A bulletin: each piece in its emotion's voice, the pauses silent, one track
// over the whole, an emotion cue wherever the emotion or its intensity changes.
eng::Result<Speech> scriptSpeech(const SayOptions& o) {
  auto script = app::loadPresenterScript(o.script, {.emotion = o.emotion, .intensity = o.intensity});
  if (!script) return script.error();
  Speech speech;
  std::vector<facial::TimedPhoneme> phonemes;
  for (const app::ScriptSegment& segment : script->segments) {
    if (segment.kind == app::ScriptSegment::Kind::Pause) {  // never first: the rate is known
      speech.samples.resize(speech.samples.size() + size_t(segment.seconds * float(speech.sampleRate)), 0.0f);
      continue;
    }
    const EmotionCue cue{.time = speech.seconds(), .emotion = segment.emotion, .intensity = segment.intensity};
    if (speech.emotions.empty() || speech.emotions.back().emotion != cue.emotion ||
        speech.emotions.back().intensity != cue.intensity)
      speech.emotions.push_back(cue);
    const std::string where = o.script + ":" + std::to_string(segment.line) + ": ";
    if (auto spoken = speakInto(speech, phonemes, segment.text, o.language, cue); !spoken)
      return spoken.error().prefixed(where);
    if (speech.seconds() > audio::kMaxSpeechSeconds)
      return eng::Error{eng::ErrorKind::TooLarge, where + "the bulletin runs past " +
                                                      std::to_string(int(audio::kMaxSpeechSeconds / 60)) + " minutes"};
  }
  return withTrack(std::move(speech), phonemes);
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

eng::Result<Speech> syllableSpeech(Speech speech, const SayOptions& o) {
  auto envelope = audio::syllableEnvelope(speech.samples, speech.sampleRate, o.fps);
  if (!envelope) return envelope.error().prefixed(o.audio + ": ");
  const std::vector<facial::TimedViseme> cues = visemesFromEnvelope(*envelope);
  if (cues.empty()) return eng::Error{eng::ErrorKind::Malformed, o.audio + ": no sound to follow"};
  return withTrack(std::move(speech), cues);
}

// The transcript force-aligned to the recording (English: pocketsphinx's
// model); when that fails, one note and the syllables.
eng::Result<Speech> alignedSpeech(Speech speech, const SayOptions& o) {
  auto aligned = audio::alignTranscript(speech.samples, speech.sampleRate, o.text);
  if (aligned && !aligned->phonemes.empty()) {
    std::vector<facial::TimedPhoneme> phonemes;
    audio::appendTrackPhonemes(aligned->phonemes, 0.0f, phonemes);
    return withTrack(std::move(speech), phonemes);
  }
  const std::string why = aligned ? "no phonemes aligned" : aligned.error().message;
  speech.notes.push_back("--text not aligned to " + o.audio + " (" + why + "); the mouth follows its syllables instead");
  return syllableSpeech(std::move(speech), o);
}

eng::Result<Speech> recordedSpeech(const SayOptions& o) {
  auto clip = audio::readAudioFile(o.audio);
  if (!clip) return clip.error();
  Speech speech;
  speech.sampleRate = clip->sampleRate;
  speech.samples = std::move(clip->samples);
  speech.emotions = {{.time = 0.0f, .emotion = o.emotion, .intensity = o.intensity}};
  if (!o.cues.empty()) {
    auto cues = readCues(o.cues);
    if (!cues) return cues.error();
    return withTrack(std::move(speech), *cues);
  }
  return o.text.empty() ? syllableSpeech(std::move(speech), o) : alignedSpeech(std::move(speech), o);
}

}  // namespace

eng::Result<Speech> speechFor(const SayOptions& o) {
  if (!o.script.empty()) {
    if (!o.text.empty() || !o.audio.empty() || !o.cues.empty())
      return eng::Error{kInvalid, "--script " + o.script + " says its own text: give no TEXT, --audio or --cues with it"};
    return scriptSpeech(o);
  }
  if (!o.cues.empty() && o.audio.empty())
    return eng::Error{kInvalid, "--cues " + o.cues + " needs --audio FILE (the voice)"};
  if (!o.cues.empty() && !o.text.empty())
    return eng::Error{kInvalid, "give --cues or --text with --audio, not both (the cues already time the mouth)"};
  return o.audio.empty() ? synthesizedSpeech(o) : recordedSpeech(o);
}

// The dominant viseme sampled every 10 ms, equal neighbours merged.
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

}  // namespace cli::say
