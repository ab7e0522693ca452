#include "audio/spoken_line.h"

namespace audio {

eng::Result<SpokenLine> speakLine(std::string_view text, const SpeechOptions& options) {
  auto spoken = synthesize(text, options);
  if (!spoken) return spoken.error();
  SpokenLine line;
  line.sampleRate = spoken->sampleRate;
  line.samples.reserve(spoken->samples.size());
  for (int16_t s : spoken->samples) line.samples.push_back(float(s) / 32768.0f);
  std::vector<facial::TimedPhoneme> phonemes;
  phonemes.reserve(spoken->phonemes.size());
  for (const TimedPhoneme& p : spoken->phonemes) {
    // espeak-ng gives a few zero-length phonemes (in seconds as floats, a
    // one-sample one is too): nothing shows in no time, and the track's
    // builder refuses them.
    const float start = float(p.start), end = float(p.end);
    if (end > start) phonemes.push_back({.ipa = p.ipa, .start = start, .end = end});
  }
  auto built = facial::VisemeTrackBuilder{}.build(phonemes);
  if (!built) return built.error();
  line.track = std::make_shared<const facial::VisemeTrack>(std::move(built->track));
  line.warnings = std::move(built->warnings);
  return line;
}

}  // namespace audio
