#pragma once
// Helpers shared by the audio tests.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "audio/speech_synthesis.h"

namespace audio_test {

inline std::vector<float> toFloat(const std::vector<int16_t>& samples) {
  std::vector<float> out(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) out[i] = samples[i] / 32768.0f;
  return out;
}

inline std::vector<float> tone(double hertz, double seconds, int sampleRate, float amplitude = 0.5f) {
  std::vector<float> out(size_t(seconds * sampleRate));
  for (size_t i = 0; i < out.size(); ++i) out[i] = amplitude * float(std::sin(2 * std::numbers::pi * hertz * double(i) / sampleRate));
  return out;
}

}  // namespace audio_test
