#pragma once
// Lip sync as data: timed phonemes (or visemes) in, an immutable VisemeTrack
// out, built offline (VisemeTrackBuilder) and sampled per frame at the host's
// audio-clock time (VisemeSampleJob), ozz-animation style: the builder does
// every decision once, the job only interpolates.
//
// The track holds, per channel (the 15 visemes, then jaw opening, lip closure
// and lip rounding), a sorted curve of linear keys. Coarticulation is a
// dominance blend (Cohen & Massaro 1993, "Modeling coarticulation in
// synthetic visual speech"): every phoneme has a dominance over time, a
// plateau over its interval with Gaussian tails before and after; a viseme's
// weight is its share of the summed dominance, so the visemes at one instant
// sum to 1. The rules below (speech_rules) shape those dominances and add the
// constraints a blend alone misses (lips must close for p/b/m).
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/speech/viseme.h"

namespace facial {

// One phoneme as an aligner or espeak-ng gives it: IPA, seconds.
struct TimedPhoneme {
  std::string ipa;
  float start = 0;
  float end = 0;
};

// One viseme cue (Rhubarb, Azure, word timings, the project's viseme JSON).
struct TimedViseme {
  Viseme viseme = Viseme::sil;
  float start = 0;
  float end = 0;
};

// Input bounds against hostile or broken files: the cue count and the latest
// time a track may reach (the builder works on a fixed time grid).
inline constexpr size_t kMaxSpeechCues = 1'000'000;
inline constexpr float kMaxSpeechSeconds = 4.0f * 3600.0f;

// Checks cues in their order: times finite, start >= 0, end > start, not
// before the previous cue (unsorted) nor inside it (overlapping), end within
// kMaxSpeechSeconds. accept() fails Malformed (TooLarge past the limit) with
// the problem alone, callers put the cue's name (index, JSON pointer, line)
// in front; an accepted cue becomes the previous one.
class CueOrderCheck {
 public:
  eng::Result<void> accept(float start, float end);

 private:
  float previousStart_ = -std::numeric_limits<float>::infinity();
  float previousEnd_ = -std::numeric_limits<float>::infinity();
};

// The coarticulation rules' constants (seconds unless said otherwise).
namespace speech_rules {
// The grid the builder evaluates the blend on; keys are then thinned.
inline constexpr float kSampleStep = 0.005f;
// Vowel anticipation: a vowel's dominance rises this long (Gaussian width)
// before its onset, so its shape forms during the consonants before it
// (Cohen & Massaro's anticipatory coarticulation; Rhubarb's rough animation
// likewise backtracks vowel shapes by up to 20 cs).
inline constexpr float kVowelAnticipation = 0.08f;
// Rounding spreads further: lip rounding of a coming O/U starts across several
// consonants (the classic "s" of "stew" is already rounded).
inline constexpr float kRoundingAnticipation = 0.15f;
// After a vowel its shape fades over this (carry-over coarticulation).
inline constexpr float kVowelCarryOver = 0.05f;
// Consonants are brief gestures: narrow tails on both sides.
inline constexpr float kConsonantSpread = 0.03f;
// Dominance (the weight a segment holds against its neighbours): lip
// consonants win over the vowels around them within their own interval (the
// lips must do their gesture), tongue consonants share with them. Their tails
// are weak (a quick, precise gesture; p/b/m's closure has its own ramps), so
// the vowel between two bilabials ("mama", "Bob") still owns its interval.
inline constexpr float kLipConsonantDominance = 2.5f;  // PP, FF
inline constexpr float kLipConsonantTailDominance = 0.5f;
inline constexpr float kStrongEdge = 0.012f;  // the width over which the extra dominance fades
inline constexpr float kDefaultDominance = 1.0f;
inline constexpr float kTransparentDominance = 0.5f;  // h, ʔ, unmapped: the neighbour's shape
// Short phonemes never dropped: a phoneme shorter than kMinVisible gets its
// dominance raised by kMinVisible / duration (at most kMaxShortBoost), so a
// 20 ms consonant still peaks above half its shape (Rhubarb keeps shapes at
// least 7 cs for the same reason, by retiming instead).
inline constexpr float kMinVisible = 0.06f;
inline constexpr float kMaxShortBoost = 4.0f;
// Bilabial closure: p/b/m close the lips completely (PP = 1, lip closure 1)
// for the phoneme or at least kMinClosureHold, whatever the blend says; the
// lips close and open over kClosureRamp (a cosine) around it. Rhubarb gives
// plosives an occlusion of 4-12 cs for the same reason.
inline constexpr float kMinClosureHold = 0.04f;
inline constexpr float kClosureRamp = 0.04f;
// ... but beside a phoneme a ramp takes at most this share of it: lips part
// within about 20 ms of a release, and a full 40 ms each side would cover
// the whole vowel of "mama" and keep it closed. Never shorter than kMinClosureRamp, the fastest a cosine ramp may be under
// kMaxWeightRate with room for the blend changing under it (its steepest
// slope is pi / 2 / ramp).
inline constexpr float kMaxClosureRampShare = 0.4f;
inline constexpr float kMinClosureRamp = 0.03f;
// A bilabial next to a pause keeps the lips closed from rest into the closure
// (and back) over up to kClosureFromRest: rest and p/b/m are both closed, so
// opening between them for an anticipated vowel would flap the jaw.
inline constexpr float kClosureFromRest = 0.1f;
// Pauses: a silence shorter than kBridgedPause is bridged (the mouth keeps
// talking, Rhubarb holds the previous shape under 12 cs); one longer than
// kRestPause relaxes to rest (sil); dominance ramps smoothly in between.
inline constexpr float kBridgedPause = 0.10f;
inline constexpr float kRestPause = 0.20f;
inline constexpr float kBridgedSilenceDominance = 0.05f;
inline constexpr float kRestDominance = 2.0f;
inline constexpr float kSilenceSpread = 0.06f;
// Rest before the first and after the last phoneme (the track starts and ends at sil).
inline constexpr float kLeadIn = 0.3f;
// Mouth ownership (kOwnershipChannel): speech keeps the mouth through pauses
// shorter than kReleasePause (commas, sentence ends inside a line: the lips
// rest closed, a smile's corners stay), so the emotion's own open mouth does
// not flash between words; in longer pauses and around the line it hands the
// mouth back over kOwnershipRamp, taking it again before the next phoneme.
inline constexpr float kReleasePause = 0.6f;
inline constexpr float kOwnershipRamp = 0.25f;
// No pops: no weight changes faster than this (per second): a full swing takes
// at least 15 ms, a frame at 60 Hz. The blend stays under it by construction;
// a final per-channel limit guarantees it.
inline constexpr float kMaxWeightRate = 1.0f / 0.015f;
// Keys are dropped while linear interpolation stays within this of the grid.
inline constexpr float kKeyTolerance = 0.002f;
}  // namespace speech_rules

class VisemeTrack {
 public:
  // channel < kSpeechChannelCount: the visemes in enum order, then the MouthChannels.
  std::span<const Keyframe> channelKeys(size_t channel) const;
  std::span<const Keyframe> visemeKeys(Viseme v) const { return channelKeys(static_cast<size_t>(v)); }
  std::span<const Keyframe> mouthKeys(MouthChannel c) const {
    return channelKeys(kVisemeCount + static_cast<size_t>(c));
  }
  // The track's time range (rest before and after included); outside it the end values hold (sil).
  float startTime() const { return startTime_; }
  float endTime() const { return endTime_; }
  size_t keyCount() const { return keys_.size(); }

 private:
  friend class VisemeTrackBuilder;
  std::vector<Keyframe> keys_;  // channel after channel
  std::array<uint32_t, kSpeechChannelCount + 1> firstKey_{};
  float startTime_ = 0;
  float endTime_ = 0;
};

struct VisemeTrackBuild {
  VisemeTrack track;
  // One line per phoneme that could not be mapped ("phoneme 4 \"☃\" at 1.2 s:
  // ..."); its interval takes its neighbours' shape instead of being dropped.
  std::vector<std::string> warnings;
};

class VisemeTrackBuilder {
 public:
  // Fails InvalidArgument naming the phoneme or cue (unsorted, overlapping,
  // non-finite or negative times, empty input), TooLarge over kMaxSpeechCues
  // or past kMaxSpeechSeconds. Gaps between cues are silence.
  eng::Result<VisemeTrackBuild> build(std::span<const TimedPhoneme> phonemes) const;
  eng::Result<VisemeTrackBuild> build(std::span<const TimedViseme> visemes) const;

 private:
  static VisemeTrack assemble(std::array<std::vector<Keyframe>, kSpeechChannelCount> channels);
};

// Samples a track at `time` (the audio clock, seconds) into 15 viseme weights
// and, when asked, the 3 mouth channels and the mouth ownership. cursors: one per
// channel (kSpeechChannelCount), kept between calls: forward playback is O(1)
// amortised, seeks stay correct. Allocates nothing.
struct VisemeSampleJob {
  const VisemeTrack* track = nullptr;
  float time = 0;
  std::span<uint32_t> cursors;
  std::span<float> visemes;  // kVisemeCount
  std::span<float> mouth;    // kMouthChannelCount, or empty
  float* ownership = nullptr;  // how much speech owns the mouth now (0..1), or null
  // InvalidArgument: no track or an empty one, a span of the wrong size, a non-finite time.
  eng::Result<void> Validate() const;
  bool Run() const;
};

}  // namespace facial
