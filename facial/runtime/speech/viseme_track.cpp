#include "facial/runtime/speech/viseme_track.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "facial/runtime/json/json_document.h"
#include "facial/runtime/speech/ipa_visemes.h"
#include "facial/runtime/speech/utf8_text.h"

namespace facial {

using namespace speech_rules;

eng::Result<void> CueOrderCheck::accept(float start, float end) {
  using eng::ErrorKind;
  if (!std::isfinite(start) || !std::isfinite(end))
    return eng::makeError(ErrorKind::Malformed, "time is not a finite number");
  if (start < 0) return eng::makeError(ErrorKind::Malformed, "negative start " + formatNumber(start) + " s");
  if (end <= start)
    return eng::makeError(ErrorKind::Malformed,
                          "ends at " + formatNumber(end) + " s, not after its start " + formatNumber(start) + " s");
  if (start < previousStart_)
    return eng::makeError(ErrorKind::Malformed, "starts at " + formatNumber(start) + " s, before the previous cue (" +
                                                    formatNumber(previousStart_) + " s): cues must be in time order");
  if (start < previousEnd_)
    return eng::makeError(ErrorKind::Malformed, "starts at " + formatNumber(start) + " s, inside the previous cue (" +
                                                    formatNumber(previousStart_) + " to " + formatNumber(previousEnd_) +
                                                    " s): cues must not overlap");
  if (end > kMaxSpeechSeconds)
    return eng::makeError(ErrorKind::TooLarge, "ends at " + formatNumber(end) + " s, past the limit of " +
                                                   formatNumber(kMaxSpeechSeconds) + " s");
  previousStart_ = start;
  previousEnd_ = end;
  return {};
}

std::span<const Keyframe> VisemeTrack::channelKeys(size_t channel) const {
  return std::span<const Keyframe>(keys_).subspan(firstKey_[channel], firstKey_[channel + 1] - firstKey_[channel]);
}

namespace {

// One stretch of the mouth's plan: a viseme over [start, end] with its dominance and tails.
struct Segment {
  Viseme viseme = Viseme::sil;
  float start = 0;
  float end = 0;
  float dominance = kDefaultDominance;
  float tailDominance = kDefaultDominance;  // the tails' peak: a lip consonant wins its interval, not its neighbours'
  float lead = kConsonantSpread;   // Gaussian width before start
  float trail = kConsonantSpread;  // Gaussian width after end
  bool borrowed = false;           // h, ʔ or unmapped: a neighbour's shape, weakly, and never a lip closure
};

// The widest tail, and how far (3 widths) a tail is followed before it counts as 0.
constexpr float kWidestTail =
    std::max({kVowelAnticipation, kRoundingAnticipation, kVowelCarryOver, kConsonantSpread, kSilenceSpread});
constexpr float kReach = 3.0f * kWidestTail;

float smoothstep(float edge0, float edge1, float x) {
  const float s = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return s * s * (3.0f - 2.0f * s);
}

// The rules that set a segment's dominance and tails from its viseme and length.
void applyDominanceRules(Segment& s, float scale) {
  const float duration = s.end - s.start;
  if (s.viseme == Viseme::sil) {  // pauses: bridged when short, rest when long
    s.dominance = std::lerp(kBridgedSilenceDominance, kRestDominance, smoothstep(kBridgedPause, kRestPause, duration));
    s.lead = s.trail = kSilenceSpread;
    s.tailDominance = s.dominance;
    return;
  }
  if (isVowelViseme(s.viseme)) {  // vowel anticipation, wider for rounding
    s.lead = isRoundedViseme(s.viseme) ? kRoundingAnticipation : kVowelAnticipation;
    s.trail = kVowelCarryOver;
  }
  const bool lipConsonant = s.viseme == Viseme::PP || s.viseme == Viseme::FF;
  const float boost = duration < kMinVisible ? std::min(kMaxShortBoost, kMinVisible / duration) : 1.0f;  // short never dropped
  s.dominance = scale * (lipConsonant ? kLipConsonantDominance : kDefaultDominance) * boost;
  s.tailDominance = scale * (lipConsonant ? kLipConsonantTailDominance : kDefaultDominance) * boost;
}

// Cues in time order, gaps and both ends filled with silence, rules applied.
std::vector<Segment> planSegments(std::span<const Segment> cues) {
  std::vector<Segment> out;
  out.reserve(cues.size() * 2 + 2);
  const auto addSilence = [&](float start, float end) { out.push_back({.start = start, .end = end}); };
  addSilence(cues.front().start - kLeadIn, cues.front().start);
  for (size_t i = 0; i < cues.size(); ++i) {
    if (i > 0 && cues[i].start > cues[i - 1].end) addSilence(cues[i - 1].end, cues[i].start);
    out.push_back(cues[i]);
  }
  addSilence(cues.back().end, cues.back().end + kLeadIn);
  // Merge touching silences so that a pause is judged by its whole length.
  std::vector<Segment> merged;
  merged.reserve(out.size());
  for (const Segment& s : out) {
    if (!merged.empty() && s.viseme == Viseme::sil && merged.back().viseme == Viseme::sil)
      merged.back().end = s.end;
    else
      merged.push_back(s);
  }
  for (Segment& s : merged) applyDominanceRules(s, s.dominance);
  return merged;
}

float dominanceAt(const Segment& s, float t) {
  const float d = t < s.start ? s.start - t : t > s.end ? t - s.end : 0.0f;
  if (d == 0.0f) return s.dominance;
  const float width = t < s.start ? s.lead : s.trail;
  if (d > 3.0f * width) return 0.0f;
  const float x = d / width, edge = d / kStrongEdge;
  // The strength above the tail's falls off within kStrongEdge: continuous, no pop at the boundary.
  return s.tailDominance * std::exp(-x * x) + (s.dominance - s.tailDominance) * std::exp(-edge * edge);
}

// The closure holds of the bilabials: [start, end] widened to kMinClosureHold,
// and into a pause beside it by up to kClosureFromRest. Beside a phoneme the
// lips close and open over a ramp of at most kMaxClosureRampShare of it, so
// the vowel of "mama" still opens.
struct Hold {
  float start, end;
  float rampIn, rampOut;
};
float rampInto(const Segment& neighbour) {
  return std::clamp(kMaxClosureRampShare * (neighbour.end - neighbour.start), kMinClosureRamp, kClosureRamp);
}
std::vector<Hold> closureHolds(std::span<const Segment> segments) {
  std::vector<Hold> holds;
  const auto isPause = [&](size_t i) { return segments[i].viseme == Viseme::sil && !segments[i].borrowed; };
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    if (s.viseme != Viseme::PP || s.borrowed) continue;
    const float centre = 0.5f * (s.start + s.end), half = 0.5f * std::max(kMinClosureHold, s.end - s.start);
    Hold hold{std::min(s.start, centre - half), std::max(s.end, centre + half), kClosureRamp, kClosureRamp};
    if (i > 0 && isPause(i - 1)) {
      hold.start = std::min(hold.start, std::max(segments[i - 1].start, s.start - kClosureFromRest));
    } else if (i > 0) {
      hold.rampIn = rampInto(segments[i - 1]);
    }
    if (i + 1 < segments.size() && isPause(i + 1)) {
      hold.end = std::max(hold.end, std::min(segments[i + 1].end, s.end + kClosureFromRest));
    } else if (i + 1 < segments.size()) {
      hold.rampOut = rampInto(segments[i + 1]);
    }
    holds.push_back(hold);
  }
  return holds;
}

// How closed the lips must be at t: 1 in a hold, a cosine ramp around it.
float closureAt(std::span<const Hold> holds, size_t& first, float t) {
  while (first < holds.size() && holds[first].end + kClosureRamp < t) ++first;
  float k = 0;
  for (size_t i = first; i < holds.size() && holds[i].start - kClosureRamp <= t; ++i) {
    const bool before = t < holds[i].start;
    const float d = before ? holds[i].start - t : t > holds[i].end ? t - holds[i].end : 0.0f;
    const float ramp = before ? holds[i].rampIn : holds[i].rampOut;
    k = std::max(k, d >= ramp ? 0.0f : 0.5f * (1.0f + std::cos(std::numbers::pi_v<float> * d / ramp)));
  }
  return k;
}

// Thins one channel's grid samples into linear keys (the swing-door test):
// a sample is dropped while the line from the last key to a later sample stays
// within kKeyTolerance of every sample between. Keys are grid samples, so
// values stay in [0, 1] and no slope gets steeper than the grid's.
class KeyThinner {
 public:
  explicit KeyThinner(std::vector<Keyframe>& out) : out_(out) {}
  void add(float t, float v) {
    if (!started_) {
      emit(t, v);
      started_ = true;
      return;
    }
    if (havePrevious_) {
      const float dt = t - anchorT_, slope = (v - anchorV_) / dt;
      if (slope < low_ || slope > high_) {  // the line would miss a sample: the previous one becomes a key
        emit(prevT_, prevV_);
      }
    }
    const float dt = t - anchorT_;
    low_ = std::max(low_, (v - kKeyTolerance - anchorV_) / dt);
    high_ = std::min(high_, (v + kKeyTolerance - anchorV_) / dt);
    prevT_ = t, prevV_ = v, havePrevious_ = true;
  }
  void finish() {
    if (havePrevious_) emit(prevT_, prevV_);
  }

 private:
  void emit(float t, float v) {
    out_.push_back({.time = t, .value = v, .interpolation = KeyInterpolation::Linear});
    anchorT_ = t, anchorV_ = v, havePrevious_ = false;
    low_ = -std::numeric_limits<float>::infinity(), high_ = std::numeric_limits<float>::infinity();
  }
  std::vector<Keyframe>& out_;
  bool started_ = false, havePrevious_ = false;
  float anchorT_ = 0, anchorV_ = 0, prevT_ = 0, prevV_ = 0, low_ = 0, high_ = 0;
};

// The viseme weights at t: each viseme's share of the summed dominance of the
// segments near t (window [first, ...), advanced as t grows).
void blendAt(std::span<const Segment> segments, size_t& first, float t, std::span<float> weights) {
  std::fill(weights.begin(), weights.end(), 0.0f);
  while (first + 1 < segments.size() && segments[first].end + kReach < t) ++first;
  float total = 0;
  for (size_t i = first; i < segments.size() && segments[i].start - kReach <= t; ++i) {
    const float d = dominanceAt(segments[i], t);
    weights[static_cast<size_t>(segments[i].viseme)] += d;
    total += d;
  }
  if (total <= 0.0f) {  // cannot happen while segments tile the range; rest is the safe answer
    weights[static_cast<size_t>(Viseme::sil)] = 1.0f;
    return;
  }
  for (float& w : weights) w /= total;
}

using ChannelKeys = std::array<std::vector<Keyframe>, kSpeechChannelCount>;

// How much speech owns the mouth at t: 0 in the rests before and after the
// line and in pauses of kReleasePause or more, ramping over kOwnershipRamp
// (a smoothstep) after the phoneme before and back by the phoneme after.
float ownershipAt(std::span<const Segment> segments, size_t first, float t) {
  float release = 0.0f;
  for (size_t i = first; i < segments.size() && segments[i].start <= t; ++i) {
    const Segment& s = segments[i];
    if (t > s.end || s.viseme != Viseme::sil || s.borrowed) continue;
    const bool leadIn = i == 0, leadOut = i + 1 == segments.size();
    if (!leadIn && !leadOut && s.end - s.start < kReleasePause) continue;
    const float ramp = std::min(kOwnershipRamp, leadIn || leadOut ? s.end - s.start : 0.5f * (s.end - s.start));
    const float out = leadIn ? 1.0f : smoothstep(s.start, s.start + ramp, t);
    const float back = leadOut ? 1.0f : 1.0f - smoothstep(s.end - ramp, s.end, t);
    release = std::max(release, std::min(out, back));
  }
  return 1.0f - release;
}

MouthShape mouthOf(std::span<const float> w) {
  MouthShape mouth{0, 0, 0};
  for (size_t v = 0; v < kVisemeCount; ++v) {
    const MouthShape& shape = mouthShapeOf(static_cast<Viseme>(v));
    mouth.jawOpen += w[v] * shape.jawOpen;
    mouth.lipClosure += w[v] * shape.lipClosure;
    mouth.lipRounding += w[v] * shape.lipRounding;
  }
  return mouth;
}

// Evaluates the rules on the grid and thins each channel into keys.
ChannelKeys keysFromSegments(std::span<const Segment> segments) {
  const std::vector<Hold> holds = closureHolds(segments);
  const float t0 = segments.front().start, t1 = segments.back().end;
  // A uniform grid no coarser than kSampleStep that ends exactly at t1.
  const size_t intervals = std::max<size_t>(1, static_cast<size_t>(std::ceil((t1 - t0) / kSampleStep)));
  const float step = (t1 - t0) / static_cast<float>(intervals);
  ChannelKeys channelKeys;
  std::vector<KeyThinner> thinners;
  thinners.reserve(kSpeechChannelCount);
  for (auto& keys : channelKeys) thinners.emplace_back(keys);
  std::array<float, kSpeechChannelCount> w{}, previous{};
  size_t firstSegment = 0, firstHold = 0;
  const float maxStep = kMaxWeightRate * step;
  for (size_t i = 0; i <= intervals; ++i) {
    const float t = i == intervals ? t1 : t0 + static_cast<float>(i) * step;
    const std::span<float> visemes = std::span(w).first<kVisemeCount>();
    blendAt(segments, firstSegment, t, visemes);
    // Bilabial closure overrides the blend: lips fully closed in the hold.
    const float closure = closureAt(holds, firstHold, t);
    for (float& weight : visemes) weight *= 1.0f - closure;
    visemes[static_cast<size_t>(Viseme::PP)] += closure;
    const MouthShape mouth = mouthOf(visemes);
    w[kVisemeCount + 0] = mouth.jawOpen;
    w[kVisemeCount + 1] = mouth.lipClosure;
    w[kVisemeCount + 2] = mouth.lipRounding;
    w[kOwnershipChannel] = ownershipAt(segments, firstSegment, t);
    // No pops: the per-channel rate limit (rarely active; see kMaxWeightRate).
    for (size_t c = 0; c < kSpeechChannelCount; ++c) {
      if (i > 0) w[c] = std::clamp(w[c], previous[c] - maxStep, previous[c] + maxStep);
      w[c] = std::clamp(w[c], 0.0f, 1.0f);
      thinners[c].add(t, w[c]);
    }
    previous = w;
  }
  for (KeyThinner& thinner : thinners) thinner.finish();
  return channelKeys;
}

eng::Result<void> checkCount(size_t count, std::string_view what) {
  if (count == 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "no " + std::string(what) + " to build a track from");
  if (count > kMaxSpeechCues)
    return eng::makeError(eng::ErrorKind::TooLarge, std::to_string(count) + " " + std::string(what) +
                                                        ", over the limit of " + std::to_string(kMaxSpeechCues));
  return {};
}

// A cue's times checked against the previous cue, the error naming the cue.
eng::Result<void> checkCue(std::string_view name, float start, float end, CueOrderCheck& order) {
  if (auto ok = order.accept(start, end); !ok) {
    const eng::ErrorKind kind =
        ok.error().kind == eng::ErrorKind::TooLarge ? eng::ErrorKind::TooLarge : eng::ErrorKind::InvalidArgument;
    return eng::makeError(kind, std::string(name) + ": " + ok.error().message);
  }
  return {};
}

// Phonemes with no shape of their own (h, ʔ) or none we know take the shape
// of the next shaped phoneme (h before a vowel is already that vowel's
// mouth), else of the previous one, with a weak dominance.
void resolveBorrowedShapes(std::vector<Segment>& cues, std::span<const size_t> borrowers) {
  for (size_t b : borrowers) {
    const auto shaped = [&](size_t i) { return cues[i].viseme != Viseme::sil && !cues[i].borrowed; };
    size_t from = b;
    for (size_t i = b + 1; i < cues.size() && from == b; ++i)
      if (shaped(i)) from = i;
    for (size_t i = b; i-- > 0 && from == b;)
      if (shaped(i)) from = i;
    cues[b].viseme = from == b ? Viseme::sil : cues[from].viseme;
  }
  for (size_t b : borrowers) cues[b].dominance = kTransparentDominance;
}

}  // namespace

eng::Result<VisemeTrackBuild> VisemeTrackBuilder::build(std::span<const TimedPhoneme> phonemes) const {
  ENG_TRY(checkCount(phonemes.size(), "phonemes"));
  VisemeTrackBuild result;
  std::vector<Segment> cues;
  cues.reserve(phonemes.size() + phonemes.size() / 4);
  std::vector<size_t> borrowers;
  CueOrderCheck order;
  for (size_t i = 0; i < phonemes.size(); ++i) {
    const TimedPhoneme& p = phonemes[i];
    ENG_TRY(checkCue("phoneme " + std::to_string(i) + " " + quotedForMessage(p.ipa), p.start, p.end, order));
    const std::optional<PhonemeVisemes> mapped = visemesForIpa(p.ipa);
    if (!mapped)
      result.warnings.push_back("phoneme " + std::to_string(i) + " " + quotedForMessage(p.ipa) + " at " +
                                formatNumber(p.start) +
                                " s: no viseme for its symbols; it takes its neighbours' shape");
    if (!mapped || mapped->kind == PhonemeVisemes::Kind::Transparent) {
      borrowers.push_back(cues.size());
      cues.push_back({.start = p.start, .end = p.end, .borrowed = true});
    } else if (mapped->kind == PhonemeVisemes::Kind::Silence) {
      cues.push_back({.viseme = Viseme::sil, .start = p.start, .end = p.end});
    } else if (mapped->count == 1) {
      cues.push_back({.viseme = mapped->visemes[0], .start = p.start, .end = p.end});
    } else {  // a diphthong: its start shape for 60 % of it, its end shape after (Rhubarb's diphthong timing)
      const float split = p.start + 0.6f * (p.end - p.start);
      cues.push_back({.viseme = mapped->visemes[0], .start = p.start, .end = split});
      cues.push_back({.viseme = mapped->visemes[1], .start = split, .end = p.end});
    }
  }
  resolveBorrowedShapes(cues, borrowers);
  result.track = assemble(keysFromSegments(planSegments(cues)));
  return result;
}

eng::Result<VisemeTrackBuild> VisemeTrackBuilder::build(std::span<const TimedViseme> visemes) const {
  ENG_TRY(checkCount(visemes.size(), "viseme cues"));
  std::vector<Segment> cues;
  cues.reserve(visemes.size());
  CueOrderCheck order;
  for (size_t i = 0; i < visemes.size(); ++i) {
    const TimedViseme& v = visemes[i];
    ENG_TRY(checkCue("viseme cue " + std::to_string(i), v.start, v.end, order));
    if (static_cast<size_t>(v.viseme) >= kVisemeCount)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "viseme cue " + std::to_string(i) + ": viseme " +
                                                                 std::to_string(static_cast<int>(v.viseme)) +
                                                                 " is not one of the 15");
    cues.push_back({.viseme = v.viseme, .start = v.start, .end = v.end});
  }
  VisemeTrackBuild result;
  result.track = assemble(keysFromSegments(planSegments(cues)));
  return result;
}

VisemeTrack VisemeTrackBuilder::assemble(std::array<std::vector<Keyframe>, kSpeechChannelCount> channels) {
  VisemeTrack track;
  size_t total = 0;
  for (const auto& keys : channels) total += keys.size();
  track.keys_.reserve(total);
  for (size_t c = 0; c < kSpeechChannelCount; ++c) {
    track.firstKey_[c] = static_cast<uint32_t>(track.keys_.size());
    track.keys_.insert(track.keys_.end(), channels[c].begin(), channels[c].end());
  }
  track.firstKey_[kSpeechChannelCount] = static_cast<uint32_t>(track.keys_.size());
  track.startTime_ = channels[0].front().time;
  track.endTime_ = channels[0].back().time;
  return track;
}

eng::Result<void> VisemeSampleJob::Validate() const {
  using eng::ErrorKind;
  if (!track) return eng::makeError(ErrorKind::InvalidArgument, "VisemeSampleJob: no track");
  if (track->keyCount() == 0)
    return eng::makeError(ErrorKind::InvalidArgument,
                          "VisemeSampleJob: the track is empty (not built by VisemeTrackBuilder)");
  if (cursors.size() != kSpeechChannelCount || visemes.size() != kVisemeCount ||
      (!mouth.empty() && mouth.size() != kMouthChannelCount))
    return eng::makeError(ErrorKind::InvalidArgument,
                          "VisemeSampleJob: expects " + std::to_string(kSpeechChannelCount) + " cursors, " +
                              std::to_string(kVisemeCount) + " viseme weights and 0 or " +
                              std::to_string(kMouthChannelCount) + " mouth channels; got " +
                              std::to_string(cursors.size()) + ", " + std::to_string(visemes.size()) + " and " +
                              std::to_string(mouth.size()));
  if (!std::isfinite(time)) return eng::makeError(ErrorKind::InvalidArgument, "VisemeSampleJob: time is not finite");
  return {};
}

bool VisemeSampleJob::Run() const {
  if (!Validate().ok()) return false;
  for (size_t v = 0; v < kVisemeCount; ++v) visemes[v] = sampleKeys(track->channelKeys(v), time, cursors[v]);
  for (size_t c = 0; c < mouth.size(); ++c)
    mouth[c] = sampleKeys(track->channelKeys(kVisemeCount + c), time, cursors[kVisemeCount + c]);
  if (ownership)
    *ownership = sampleKeys(track->channelKeys(kOwnershipChannel), time, cursors[kOwnershipChannel]);
  return true;
}

}  // namespace facial
