#include "audio/syllable_envelope.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace audio {
namespace {

constexpr double kHopSeconds = 0.010;       // analysis step
constexpr size_t kWindowHops = 3;           // RMS over 30 ms
constexpr size_t kSmoothingFrames = 5;        // 50 ms moving average: one syllable stays one peak
constexpr float kSilenceBelowPeakDb = 30;   // quieter than the loudest frame by this much: silence
constexpr float kSilenceFloorDb = -60;      // and always silence below this (dBFS)
constexpr float kMinProminenceDb = 3;       // a nucleus rises this much above the valleys beside it
constexpr int kMinNucleusGapFrames = 8;     // 80 ms: two nuclei closer are one syllable
constexpr int kProminenceReachFrames = 50;  // valleys searched within 0.5 s (bounded time)
constexpr float kOpenWithinDb = 6;          // Open: within this of the nucleus' level

// Second-order section (RBJ cookbook), direct form I.
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  static Biquad make(bool highPass, double cutoff, double sampleRate) {
    const double w = 2 * std::numbers::pi * cutoff / sampleRate, cosw = std::cos(w);
    const double alpha = std::sin(w) / (2 * std::numbers::sqrt2 / 2);
    const double a0 = 1 + alpha;
    Biquad f;
    f.b0 = (highPass ? (1 + cosw) : (1 - cosw)) / 2 / a0;
    f.b1 = (highPass ? -(1 + cosw) : (1 - cosw)) / a0;
    f.b2 = f.b0;
    f.a1 = -2 * cosw / a0;
    f.a2 = (1 - alpha) / a0;
    return f;
  }
  double process(double x) {
    const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1, x1 = x, y2 = y1, y1 = y;
    return y;
  }
};

// [from, to) of `width` frames centred on `frame`, cut at both ends.
std::pair<size_t, size_t> centredWindow(size_t frame, size_t width, size_t frames) {
  return {frame >= width / 2 ? frame - width / 2 : 0, std::min(frames, frame + width / 2 + 1)};
}

// Smoothed voice-band level in dBFS, one value per hop. Memory is per hop,
// not per sample (30 minutes at 48 kHz is 86 million samples).
std::vector<float> voiceBandLevels(std::span<const float> samples, int sampleRate) {
  Biquad highPass = Biquad::make(true, 300, sampleRate);
  const bool lowPassFits = 3000 < sampleRate * 0.45;
  Biquad lowPass = Biquad::make(false, 3000, sampleRate);
  const size_t hop = std::max<size_t>(1, size_t(kHopSeconds * sampleRate));
  const size_t frames = (samples.size() + hop - 1) / hop;
  std::vector<double> hopEnergy(frames, 0.0);
  for (size_t i = 0; i < samples.size(); ++i) {
    const double x = std::isfinite(samples[i]) ? samples[i] : 0.0;
    double y = highPass.process(x);
    if (lowPassFits) y = lowPass.process(y);
    hopEnergy[i / hop] += y * y;
  }
  // Each level: the mean square over kWindowHops hops centred on it.
  std::vector<float> levels(frames);
  for (size_t f = 0; f < frames; ++f) {
    const auto [from, to] = centredWindow(f, kWindowHops, frames);
    double energy = 0;
    for (size_t k = from; k < to; ++k) energy += hopEnergy[k];
    const size_t counted = std::min(samples.size(), to * hop) - from * hop;
    levels[f] = float(10 * std::log10(energy / double(counted) + 1e-12));
  }
  std::vector<float> smoothed(frames);
  for (size_t f = 0; f < frames; ++f) {
    const auto [from, to] = centredWindow(f, kSmoothingFrames, frames);
    float sum = 0;
    for (size_t k = from; k < to; ++k) sum += levels[k];
    smoothed[f] = sum / float(to - from);
  }
  return smoothed;
}

struct FrameRun {
  int from = 0, to = 0;  // [from, to) in frames
};

// Speech runs: frames above the silence level, with gaps shorter than a rest bridged.
std::vector<FrameRun> speechRuns(const std::vector<float>& levels, float silenceDb) {
  std::vector<FrameRun> runs;
  const int frames = int(levels.size());
  for (int f = 0; f < frames;) {
    if (levels[f] < silenceDb) { ++f; continue; }
    int end = f;
    while (end < frames && levels[end] >= silenceDb) ++end;
    if (!runs.empty() && (f - runs.back().to) * kHopSeconds < kMinRestSeconds) runs.back().to = end;
    else runs.push_back({f, end});
    f = end;
  }
  return runs;
}

// Prominent local maxima of `levels` within `run`, at least kMinNucleusGapFrames apart.
std::vector<int> nucleusFrames(const std::vector<float>& levels, FrameRun run, float silenceDb) {
  auto level = [&](int f) { return f < run.from || f >= run.to ? silenceDb : levels[f]; };
  std::vector<int> peaks;
  for (int f = run.from; f < run.to; ++f) {
    if (!(level(f) >= level(f - 1) && level(f) > level(f + 1))) continue;
    float leftValley = level(f), rightValley = level(f);
    for (int k = f - 1; k >= std::max(run.from - 1, f - kProminenceReachFrames) && level(k) <= level(f); --k)
      leftValley = std::min(leftValley, level(k));
    for (int k = f + 1; k <= std::min(run.to, f + kProminenceReachFrames) && level(k) <= level(f); ++k)
      rightValley = std::min(rightValley, level(k));
    if (level(f) - std::max(leftValley, rightValley) < kMinProminenceDb) continue;
    if (!peaks.empty() && f - peaks.back() < kMinNucleusGapFrames) {
      if (level(f) > level(peaks.back())) peaks.back() = f;
      continue;
    }
    peaks.push_back(f);
  }
  if (peaks.empty() && run.to > run.from)  // a run with no clear peak is still one syllable
    peaks.push_back(int(std::max_element(levels.begin() + run.from, levels.begin() + run.to) - levels.begin()));
  return peaks;
}

void appendSegment(std::vector<MouthSegment>& segments, MouthState state, double start, double end, float openness) {
  if (end <= start) return;
  if (!segments.empty() && segments.back().state == state && state != MouthState::Open) {
    segments.back().end = end;
    return;
  }
  segments.push_back({state, start, end, openness});
}

// Splits one speech run into Open (around each nucleus) and Closed segments.
void segmentRun(const std::vector<float>& levels, FrameRun run, float peakDb, float silenceDb, SyllableEnvelope& out) {
  const std::vector<int> peaks = nucleusFrames(levels, run, silenceDb);
  int cursor = run.from;
  for (size_t p = 0; p < peaks.size(); ++p) {
    const int nucleus = peaks[p];
    // The syllable ends at the lowest frame before the next nucleus.
    const int limit = p + 1 < peaks.size() ? peaks[p + 1] : run.to;
    const int boundary = p + 1 < peaks.size()
                             ? int(std::min_element(levels.begin() + nucleus, levels.begin() + limit) - levels.begin())
                             : run.to;
    const float openAbove = levels[nucleus] - kOpenWithinDb;
    int openFrom = nucleus, openTo = nucleus + 1;
    while (openFrom > cursor && levels[openFrom - 1] >= openAbove) --openFrom;
    while (openTo < boundary && levels[openTo] >= openAbove) ++openTo;
    const float openness = std::clamp((levels[nucleus] - silenceDb) / (peakDb - silenceDb), 0.2f, 1.0f);
    appendSegment(out.segments, MouthState::Closed, cursor * kHopSeconds, openFrom * kHopSeconds, 0);
    appendSegment(out.segments, MouthState::Open, openFrom * kHopSeconds, openTo * kHopSeconds, openness);
    out.nuclei.push_back((nucleus + 0.5) * kHopSeconds);
    cursor = openTo;
    if (p + 1 < peaks.size()) {
      appendSegment(out.segments, MouthState::Closed, cursor * kHopSeconds, boundary * kHopSeconds, 0);
      cursor = boundary;
    }
  }
  appendSegment(out.segments, MouthState::Closed, cursor * kHopSeconds, run.to * kHopSeconds, 0);
}

// The per-frame curve: each Open segment rises to its openness at the
// nucleus and falls to nothing at its edges; Closed and Rest are 0.
void sampleMouthCurve(double durationSeconds, SyllableEnvelope& out) {
  const size_t frames = size_t(std::ceil(durationSeconds * out.framesPerSecond));
  out.mouthOpen.assign(frames, 0.0f);
  size_t nucleusIndex = 0;
  for (const auto& segment : out.segments) {
    if (segment.state != MouthState::Open) continue;
    while (nucleusIndex + 1 < out.nuclei.size() && out.nuclei[nucleusIndex] < segment.start) ++nucleusIndex;
    const double peak = std::clamp(out.nuclei[nucleusIndex], segment.start, segment.end);
    const size_t first = size_t(std::ceil(segment.start * out.framesPerSecond));
    for (size_t i = first; i < frames && i / double(out.framesPerSecond) < segment.end; ++i) {
      const double t = i / double(out.framesPerSecond);
      const double span = t < peak ? peak - segment.start : segment.end - peak;
      const double shape = span > 0 ? 1.0 - std::abs(t - peak) / span : 1.0;
      out.mouthOpen[i] = std::max(out.mouthOpen[i], float(segment.openness * (0.5 + 0.5 * shape)));
    }
  }
}

}  // namespace

eng::Result<SyllableEnvelope> syllableEnvelope(std::span<const float> samples, int sampleRate, float framesPerSecond) {
  if (sampleRate < 1000 || sampleRate > 384000)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "syllable envelope: sample rate " + std::to_string(sampleRate) + " Hz is outside 1000..384000");
  if (!(framesPerSecond >= 1 && framesPerSecond <= 1000))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "syllable envelope: " + std::to_string(framesPerSecond) + " frames a second is outside 1..1000");
  if (samples.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "syllable envelope: no samples");
  SyllableEnvelope out;
  out.framesPerSecond = framesPerSecond;
  const double duration = double(samples.size()) / sampleRate;
  const std::vector<float> levels = voiceBandLevels(samples, sampleRate);
  const float peakDb = *std::max_element(levels.begin(), levels.end());
  const float silenceDb = std::max(kSilenceFloorDb, peakDb - kSilenceBelowPeakDb);
  int cursor = 0;
  for (const FrameRun& run : speechRuns(levels, silenceDb)) {
    appendSegment(out.segments, MouthState::Rest, cursor * kHopSeconds, run.from * kHopSeconds, 0);
    segmentRun(levels, run, peakDb, silenceDb, out);
    cursor = run.to;
  }
  appendSegment(out.segments, MouthState::Rest, cursor * kHopSeconds, duration, 0);
  // The last hop may run past the audio: the segments end where it ends.
  while (!out.segments.empty() && out.segments.back().start >= duration) out.segments.pop_back();
  if (!out.segments.empty()) out.segments.back().end = duration;
  sampleMouthCurve(duration, out);
  return out;
}

}  // namespace audio
