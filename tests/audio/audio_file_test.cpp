#include "audio/audio_file.h"

#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>

#include "tests/audio/speech_samples.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

// Writes interleaved `frames` x `channels` samples with libsndfile.
void writeSoundFile(const fs::path& path, int format, int sampleRate, int channels, const std::vector<float>& interleaved) {
  SF_INFO info{};
  info.samplerate = sampleRate;
  info.channels = channels;
  info.format = format;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(file, nullptr) << path << ": " << sf_strerror(nullptr);
  sf_writef_float(file, interleaved.data(), sf_count_t(interleaved.size() / channels));
  sf_close(file);
}

float rms(const std::vector<float>& samples) {
  double sum = 0;
  for (float x : samples) sum += double(x) * x;
  return samples.empty() ? 0.0f : float(std::sqrt(sum / samples.size()));
}

TEST(AudioFile, StereoWavReadsAsMonoAverage) {
  const fs::path dir = testing_support::freshTempDir("audio_file_wav");
  std::vector<float> interleaved;
  for (int i = 0; i < 8000; ++i) {
    interleaved.push_back(0.5f);   // left
    interleaved.push_back(-0.25f); // right
  }
  writeSoundFile(dir / "stereo.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 16000, 2, interleaved);
  auto clip = audio::readAudioFile(dir / "stereo.wav");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->sampleRate, 16000);
  ASSERT_EQ(clip->samples.size(), 8000u);
  EXPECT_NEAR(clip->samples[100], 0.125f, 1e-3f);
  EXPECT_DOUBLE_EQ(clip->durationSeconds(), 0.5);
}

TEST(AudioFile, OggVorbisFlacAndMp3RoundTrip) {
  const fs::path dir = testing_support::freshTempDir("audio_file_ogg");
  const std::vector<float> tone = audio_test::tone(440, 1.0, 44100);
  for (const auto& [name, format] : {std::pair{"tone.ogg", SF_FORMAT_OGG | SF_FORMAT_VORBIS},
                                     std::pair{"tone.flac", SF_FORMAT_FLAC | SF_FORMAT_PCM_16},
                                     std::pair{"tone.mp3", SF_FORMAT_MPEG | SF_FORMAT_MPEG_LAYER_III}}) {
    writeSoundFile(dir / name, format, 44100, 1, tone);
    auto clip = audio::readAudioFile(dir / name);
    ASSERT_TRUE(clip.ok()) << clip.error().message;
    EXPECT_EQ(clip->sampleRate, 44100) << name;
    EXPECT_NEAR(clip->durationSeconds(), 1.0, 0.06) << name;  // MP3 adds its encoder delay
    EXPECT_NEAR(rms(clip->samples), rms(tone), 0.02f) << name;  // a 0.5 sine: 0.354
  }
}

TEST(AudioFile, SilentFileReadsAsZeros) {
  const fs::path dir = testing_support::freshTempDir("audio_file_silent");
  writeSoundFile(dir / "silence.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 22050, 1, std::vector<float>(22050, 0.0f));
  auto clip = audio::readAudioFile(dir / "silence.wav");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->samples.size(), 22050u);
  EXPECT_EQ(rms(clip->samples), 0.0f);
}

void expectOneLineNaming(const eng::Result<audio::AudioClip>& clip, const fs::path& path, eng::ErrorKind kind) {
  ASSERT_FALSE(clip.ok()) << path;
  EXPECT_EQ(clip.error().kind, kind) << clip.error().message;
  EXPECT_NE(clip.error().message.find(path.string()), std::string::npos) << clip.error().message;
  EXPECT_EQ(clip.error().message.find('\n'), std::string::npos) << clip.error().message;
}

TEST(AudioFile, MissingCorruptEmptyAndFolderAreOneLineErrors) {
  const fs::path dir = testing_support::freshTempDir("audio_file_bad");
  expectOneLineNaming(audio::readAudioFile(dir / "missing.wav"), dir / "missing.wav", eng::ErrorKind::NotFound);
  testing_support::writeFile(dir / "garbage.wav", std::string(4096, '\x5a'));
  expectOneLineNaming(audio::readAudioFile(dir / "garbage.wav"), dir / "garbage.wav", eng::ErrorKind::Malformed);
  testing_support::writeFile(dir / "empty.ogg", "");
  expectOneLineNaming(audio::readAudioFile(dir / "empty.ogg"), dir / "empty.ogg", eng::ErrorKind::Malformed);
  writeSoundFile(dir / "no_samples.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 22050, 1, {});
  expectOneLineNaming(audio::readAudioFile(dir / "no_samples.wav"), dir / "no_samples.wav", eng::ErrorKind::Malformed);
  expectOneLineNaming(audio::readAudioFile(dir), dir, eng::ErrorKind::Io);
}

TEST(AudioFile, TruncatedWavKeepsWhatIsThere) {
  const fs::path dir = testing_support::freshTempDir("audio_file_truncated");
  writeSoundFile(dir / "whole.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 8000, 1, audio_test::tone(200, 1.0, 8000));
  const fs::path cut = dir / "cut.wav";
  fs::copy_file(dir / "whole.wav", cut);
  fs::resize_file(cut, 44 + 2 * 4000);  // the header says 8000 samples, 4000 are there
  auto clip = audio::readAudioFile(cut);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->samples.size(), 4000u);
}

TEST(AudioFile, OverTheLengthLimitIsRefusedWithTheLimit) {
  const fs::path dir = testing_support::freshTempDir("audio_file_long");
  // 31 minutes at a tiny (but valid) rate of 100 Hz: a small file past the limit.
  writeSoundFile(dir / "long.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16, 100, 1, std::vector<float>(100 * 60 * 31, 0.1f));
  auto clip = audio::readAudioFile(dir / "long.wav");
  expectOneLineNaming(clip, dir / "long.wav", eng::ErrorKind::TooLarge);
  EXPECT_NE(clip.error().message.find("1800 s"), std::string::npos) << clip.error().message;
}

TEST(AudioFile, WavWriterRoundTripsClipsAndLeavesNoPartial) {
  const fs::path dir = testing_support::freshTempDir("audio_file_write");
  std::vector<float> samples;
  for (int i = 0; i < 22050; ++i) samples.push_back(0.5f * std::sin(float(i) * 0.05f));
  samples[10] = 3.0f;  // clips to full scale, never wraps to negative
  ASSERT_TRUE(audio::writeWavFile(dir / "voice.wav", samples, 22050).ok());
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);
  auto clip = audio::readAudioFile(dir / "voice.wav");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->sampleRate, 22050);
  ASSERT_EQ(clip->samples.size(), samples.size());
  EXPECT_NEAR(clip->samples[1000], samples[1000], 1e-4f);
  EXPECT_GT(clip->samples[10], 0.99f);

  auto unwritable = audio::writeWavFile(dir / "no_such_folder" / "voice.wav", samples, 22050);
  ASSERT_FALSE(unwritable.ok());
  EXPECT_NE(unwritable.error().message.find("no_such_folder/voice.wav: cannot write"), std::string::npos)
      << unwritable.error().message;
}

TEST(AudioFile, ReadsTheSharedFrenchRecording) {
  FACIAL_REQUIRE_SHARED();
  const fs::path path = testing_support::sharedDir() / "speech" / "bonjour.ogg";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent";
  auto clip = audio::readAudioFile(path);
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_GT(clip->sampleRate, 8000);
  EXPECT_NEAR(clip->durationSeconds(), 7.36, 0.1);  // Rhubarb's bonjour.json says 7.36 s
  EXPECT_GT(rms(clip->samples), 0.01f);
}

}  // namespace
