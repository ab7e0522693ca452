#pragma once
// Helpers shared by the speech tests: phoneme lists and sampling a built track.
#include <algorithm>
#include <array>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "facial/runtime/speech/viseme_track.h"

namespace facial::speech_test {

// Phonemes laid end to end from `start`, each {ipa, duration}.
inline std::vector<TimedPhoneme> phonemeRun(std::initializer_list<std::pair<const char*, float>> items,
                                            float start = 0.0f) {
  std::vector<TimedPhoneme> out;
  for (const auto& [ipa, duration] : items) {
    out.push_back({ipa, start, start + duration});
    start += duration;
  }
  return out;
}

// The 18 channels (15 visemes, then the mouth channels) at `time`.
struct Frame {
  std::array<float, kVisemeCount> visemes{};
  std::array<float, kMouthChannelCount> mouth{};
  float ownership = 0;  // how much speech owns the mouth
  float operator[](Viseme v) const { return visemes[static_cast<size_t>(v)]; }
  float operator[](MouthChannel c) const { return mouth[static_cast<size_t>(c)]; }
  float sum() const {
    float s = 0;
    for (float w : visemes) s += w;
    return s;
  }
};

inline Frame sampleAt(const VisemeTrack& track, float time) {
  Frame f;
  std::array<uint32_t, kSpeechChannelCount> cursors{};
  VisemeSampleJob{.track = &track, .time = time, .cursors = cursors, .visemes = f.visemes, .mouth = f.mouth,
                  .ownership = &f.ownership}
      .Run();
  return f;
}

inline VisemeTrack buildOrDie(const std::vector<TimedPhoneme>& phonemes) {
  auto built = VisemeTrackBuilder{}.build(phonemes);
  if (!built) throw std::runtime_error(built.error().message);
  return std::move(built->track);
}

// The largest weight of `v` over [from, to], sampled every millisecond.
inline float peakOver(const VisemeTrack& track, Viseme v, float from, float to) {
  float peak = 0;
  for (float t = from; t <= to; t += 0.001f) peak = std::max(peak, sampleAt(track, t)[v]);
  return peak;
}

}  // namespace facial::speech_test
