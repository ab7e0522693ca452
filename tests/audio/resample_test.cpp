#include "audio/resample.h"

#include <gtest/gtest.h>

#include "tests/audio/speech_samples.h"

namespace {

size_t upwardZeroCrossings(const std::vector<float>& samples) {
  size_t count = 0;
  for (size_t i = 1; i < samples.size(); ++i) count += samples[i - 1] < 0 && samples[i] >= 0;
  return count;
}

TEST(Resample, KeepsDurationAndPitch) {
  const std::vector<float> tone = audio_test::tone(440, 1.0, 22050);
  for (int rate : {16000, 48000}) {
    auto resampled = audio::resampleMono(tone, 22050, rate);
    ASSERT_TRUE(resampled.ok()) << resampled.error().message;
    EXPECT_NEAR(double(resampled->size()), rate, rate * 0.002) << rate;
    EXPECT_NEAR(double(upwardZeroCrossings(*resampled)), 440.0, 2.0) << rate;  // still 440 Hz
  }
}

TEST(Resample, SameRateCopiesAndBadRatesAreRefused) {
  const std::vector<float> samples = {0.1f, -0.2f, 0.3f};
  auto same = audio::resampleMono(samples, 16000, 16000);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(*same, samples);
  EXPECT_FALSE(audio::resampleMono(samples, 0, 16000).ok());
  EXPECT_FALSE(audio::resampleMono(samples, 16000, 10000000).ok());
}

}  // namespace
