#include "audio/spoken_line.h"

namespace audio {
namespace {

struct EmotionShade {
  std::string_view emotion;
  float ratePercent;
  float pitchPercent;
};
constexpr EmotionShade kEmotionShades[] = {
    {"happy", 108, 115}, {"sad", 85, 85},        {"anger", 105, 95},   {"fear", 110, 120},
    {"surprise", 110, 125}, {"disgust", 95, 90},
};

}  // namespace

SpeechOptions emotionalVoice(std::string language, std::string_view emotion, float intensity) {
  SpeechOptions voice{.language = std::move(language)};
  for (const EmotionShade& shade : kEmotionShades) {
    if (shade.emotion != emotion) continue;
    voice.ratePercent = 100.0f + (shade.ratePercent - 100.0f) * intensity;
    voice.pitchPercent = 100.0f + (shade.pitchPercent - 100.0f) * intensity;
  }
  return voice;
}

void appendTrackPhonemes(std::span<const TimedPhoneme> spoken, float offset, std::vector<facial::TimedPhoneme>& out) {
  for (const TimedPhoneme& p : spoken) {
    // espeak-ng gives a few zero-length phonemes (in seconds as floats, a
    // one-sample one is too): nothing shows in no time, and the track's
    // builder refuses them.
    const float start = offset + float(p.start), end = offset + float(p.end);
    if (end > start) out.push_back({.ipa = p.ipa, .start = start, .end = end});
  }
}

eng::Result<SpokenLine> speakLine(std::string_view text, const SpeechOptions& options) {
  auto spoken = synthesize(text, options);
  if (!spoken) return spoken.error();
  SpokenLine line;
  line.sampleRate = spoken->sampleRate;
  line.samples.reserve(spoken->samples.size());
  for (int16_t s : spoken->samples) line.samples.push_back(float(s) / 32768.0f);
  std::vector<facial::TimedPhoneme> phonemes;
  phonemes.reserve(spoken->phonemes.size());
  appendTrackPhonemes(spoken->phonemes, 0.0f, phonemes);
  auto built = facial::VisemeTrackBuilder{}.build(phonemes);
  if (!built) return built.error();
  line.track = std::make_shared<const facial::VisemeTrack>(std::move(built->track));
  line.warnings = std::move(built->warnings);
  return line;
}

}  // namespace audio
