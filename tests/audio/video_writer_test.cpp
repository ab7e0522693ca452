#include "audio/video_writer.h"

#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <algorithm>
#include <cmath>
#include <vector>

#include "tests/audio/speech_samples.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

struct VideoFacts {
  std::string videoCodec, audioCodec;
  int width = 0, height = 0, audioRate = 0;
  double durationSeconds = 0;
  int videoPackets = 0, audioPackets = 0;
  double audioRms = 0;  // decoded
};

// Decodes every audio packet's samples (any sample format the decoder gives: float or 16-bit, planar or not).
void accumulateAudio(AVCodecContext* decoder, AVFrame* frame, double& sumSquares, int64_t& count) {
  while (avcodec_receive_frame(decoder, frame) == 0) {
    const auto format = AVSampleFormat(frame->format);
    for (int i = 0; i < frame->nb_samples; ++i) {
      double x = 0;
      if (format == AV_SAMPLE_FMT_FLTP || format == AV_SAMPLE_FMT_FLT) x = reinterpret_cast<const float*>(frame->data[0])[i];
      else if (format == AV_SAMPLE_FMT_S16P || format == AV_SAMPLE_FMT_S16) x = reinterpret_cast<const int16_t*>(frame->data[0])[i] / 32768.0;
      sumSquares += x * x;
      ++count;
    }
  }
}

VideoFacts inspect(const fs::path& path) {
  VideoFacts facts;
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, path.c_str(), nullptr, nullptr) < 0) return facts;
  avformat_find_stream_info(input, nullptr);
  facts.durationSeconds = input->duration / double(AV_TIME_BASE);
  AVCodecContext* decoder = nullptr;
  int audioIndex = -1;
  for (unsigned i = 0; i < input->nb_streams; ++i) {
    const AVCodecParameters* p = input->streams[i]->codecpar;
    if (p->codec_type == AVMEDIA_TYPE_VIDEO) {
      facts.videoCodec = avcodec_get_name(p->codec_id);
      facts.width = p->width;
      facts.height = p->height;
    } else if (p->codec_type == AVMEDIA_TYPE_AUDIO) {
      facts.audioCodec = avcodec_get_name(p->codec_id);
      facts.audioRate = p->sample_rate;
      audioIndex = int(i);
      decoder = avcodec_alloc_context3(avcodec_find_decoder(p->codec_id));
      avcodec_parameters_to_context(decoder, p);
      avcodec_open2(decoder, decoder->codec, nullptr);
    }
  }
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  double sumSquares = 0;
  int64_t count = 0;
  while (av_read_frame(input, packet) >= 0) {
    if (packet->stream_index == audioIndex) {
      ++facts.audioPackets;
      if (avcodec_send_packet(decoder, packet) == 0) accumulateAudio(decoder, frame, sumSquares, count);
    } else {
      ++facts.videoPackets;
    }
    av_packet_unref(packet);
  }
  facts.audioRms = count ? std::sqrt(sumSquares / count) : 0.0;
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  avformat_close_input(&input);
  return facts;
}

// A moving gradient, so the encoder has something to encode.
std::vector<uint8_t> gradientFrame(int width, int height, int index) {
  std::vector<uint8_t> rgba(size_t(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
      p[0] = uint8_t(x * 4 + index * 8), p[1] = uint8_t(y * 4), p[2] = uint8_t(128), p[3] = 255;
    }
  return rgba;
}

void writeOneSecondClip(const fs::path& path, int sampleRate) {
  const std::vector<float> tone = audio_test::tone(440, 1.0, sampleRate, 0.5f);
  auto writer = audio::VideoWriter::create(path, {.width = 64, .height = 48, .framesPerSecond = 25,
                                                  .audioSamples = tone, .audioSampleRate = sampleRate});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  for (int i = 0; i < 25; ++i) ASSERT_TRUE(writer->addFrame(gradientFrame(64, 48, i)).ok());
  EXPECT_FALSE(fs::exists(path)) << "the video appears only when finished";
  EXPECT_TRUE(fs::exists(path.string() + ".partial"));
  auto finished = writer->finish();
  ASSERT_TRUE(finished.ok()) << finished.error().message;
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
}

// The clip of writeOneSecondClip as read back: both streams, every frame, the tone.
void expectOneSecondClip(const fs::path& path, const std::string& videoCodec, const std::string& audioCodec, int audioRate) {
  const VideoFacts facts = inspect(path);
  EXPECT_EQ(facts.videoCodec, videoCodec);
  EXPECT_EQ(facts.audioCodec, audioCodec);
  EXPECT_EQ(facts.audioRate, audioRate);
  EXPECT_EQ(facts.width, 64);
  EXPECT_EQ(facts.height, 48);
  EXPECT_EQ(facts.videoPackets, 25);
  EXPECT_GT(facts.audioPackets, 10);
  EXPECT_NEAR(facts.durationSeconds, 1.0, 0.1);
  EXPECT_NEAR(facts.audioRms, 0.5 / std::sqrt(2.0), 0.05);  // the tone, not silence
}

TEST(VideoWriter, Mp4IsH264AndAacWithTheToneAndEveryFrame) {
  const fs::path path = testing_support::freshTempDir("video_writer_mp4") / "clip.mp4";
  writeOneSecondClip(path, 22050);
  expectOneSecondClip(path, "h264", "aac", 22050);  // espeak's rate: AAC takes it as it is
}

TEST(VideoWriter, WebmIsVp9AndOpusWithTheToneAndEveryFrame) {
  const fs::path path = testing_support::freshTempDir("video_writer_webm") / "clip.webm";
  writeOneSecondClip(path, 22050);
  expectOneSecondClip(path, "vp9", "opus", 48000);  // Opus takes only 48 kHz: resampled
}

TEST(VideoWriter, SilentVideoHasNoAudioStream) {
  const fs::path path = testing_support::freshTempDir("video_writer_silent") / "clip.mp4";
  auto writer = audio::VideoWriter::create(path, {.width = 32, .height = 32, .framesPerSecond = 10});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(writer->addFrame(gradientFrame(32, 32, i)).ok());
  ASSERT_TRUE(writer->finish().ok());
  const VideoFacts facts = inspect(path);
  EXPECT_EQ(facts.videoPackets, 10);
  EXPECT_TRUE(facts.audioCodec.empty());
}

TEST(VideoWriter, UnfinishedVideoLeavesNoFile) {
  const fs::path dir = testing_support::freshTempDir("video_writer_unfinished");
  {
    const std::vector<float> tone = audio_test::tone(440, 0.5, 16000);
    auto writer = audio::VideoWriter::create(dir / "clip.mp4", {.width = 32, .height = 32, .framesPerSecond = 10,
                                                                .audioSamples = tone, .audioSampleRate = 16000});
    ASSERT_TRUE(writer.ok()) << writer.error().message;
    ASSERT_TRUE(writer->addFrame(gradientFrame(32, 32, 0)).ok());
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// The mean luma (Y, 16..235) of each decoded video frame, in presentation order.
std::vector<double> frameLumas(const fs::path& path) {
  std::vector<double> lumas;
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, path.c_str(), nullptr, nullptr) < 0) return lumas;
  const AVCodec* codec = nullptr;
  const int stream = avformat_find_stream_info(input, nullptr) >= 0
                         ? av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0) : -1;
  AVCodecContext* decoder = stream >= 0 ? avcodec_alloc_context3(codec) : nullptr;
  if (decoder && avcodec_parameters_to_context(decoder, input->streams[stream]->codecpar) >= 0 &&
      avcodec_open2(decoder, codec, nullptr) >= 0) {
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    const auto receive = [&] {
      while (avcodec_receive_frame(decoder, frame) == 0) {
        double sum = 0;
        for (int y = 0; y < frame->height; ++y)
          for (int x = 0; x < frame->width; ++x) sum += frame->data[0][y * frame->linesize[0] + x];
        lumas.push_back(sum / (frame->width * frame->height));
      }
    };
    while (av_read_frame(input, packet) >= 0) {
      if (packet->stream_index == stream && avcodec_send_packet(decoder, packet) == 0) receive();
      av_packet_unref(packet);
    }
    if (avcodec_send_packet(decoder, nullptr) == 0) receive();
    av_frame_free(&frame);
    av_packet_free(&packet);
  }
  avcodec_free_context(&decoder);
  avformat_close_input(&input);
  return lumas;
}

// addFrame() copies the frame and queues it for the writer's encoder thread:
// many more frames than the queue holds, from one buffer the caller overwrites
// at once, come out all there, in order, each with its own picture.
TEST(VideoWriter, QueuedFramesKeepTheirOrderAndPictures) {
  const fs::path path = testing_support::freshTempDir("video_writer_queue") / "clip.mp4";
  constexpr int kFrames = 40;
  auto writer = audio::VideoWriter::create(path, {.width = 32, .height = 32, .framesPerSecond = 25});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  std::vector<uint8_t> rgba(32 * 32 * 4);
  for (int i = 0; i < kFrames; ++i) {
    std::fill(rgba.begin(), rgba.end(), uint8_t(20 + i * 5));  // grey, brighter each frame
    ASSERT_TRUE(writer->addFrame(rgba).ok());
    std::fill(rgba.begin(), rgba.end(), uint8_t(0));  // the caller reuses its buffer at once
  }
  ASSERT_TRUE(writer->finish().ok());
  const std::vector<double> lumas = frameLumas(path);
  ASSERT_EQ(lumas.size(), size_t(kFrames));
  for (int i = 0; i < kFrames; ++i)
    EXPECT_NEAR(lumas[i], 16 + 219.0 * (20 + i * 5) / 255, 2.0) << "frame " << i;
}

TEST(VideoWriter, AbandonedWithAFullQueueLeavesNoFile) {
  const fs::path dir = testing_support::freshTempDir("video_writer_abandoned");
  {
    auto writer = audio::VideoWriter::create(dir / "clip.mp4", {.width = 64, .height = 64, .framesPerSecond = 30});
    ASSERT_TRUE(writer.ok()) << writer.error().message;
    for (int i = 0; i < 20; ++i) ASSERT_TRUE(writer->addFrame(gradientFrame(64, 64, i)).ok());
  }  // destroyed while frames may still wait for the encoder
  EXPECT_TRUE(fs::is_empty(dir));
}

void expectRefused(const fs::path& path, const audio::VideoSettings& settings, eng::ErrorKind kind) {
  auto writer = audio::VideoWriter::create(path, settings);
  ASSERT_FALSE(writer.ok()) << path;
  EXPECT_EQ(writer.error().kind, kind) << writer.error().message;
  EXPECT_NE(writer.error().message.find(path.string()), std::string::npos) << writer.error().message;
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
}

TEST(VideoWriter, RefusesBadArgumentsNamingTheFile) {
  const fs::path dir = testing_support::freshTempDir("video_writer_bad");
  const std::vector<float> tone = audio_test::tone(440, 0.1, 16000);
  using eng::ErrorKind;
  expectRefused(dir / "clip.avi", {.width = 32, .height = 32}, ErrorKind::Unsupported);
  expectRefused(dir / "clip.mp4", {.width = 33, .height = 32}, ErrorKind::InvalidArgument);
  expectRefused(dir / "clip.mp4", {.width = 0, .height = 32}, ErrorKind::InvalidArgument);
  expectRefused(dir / "clip.mp4", {.width = 32, .height = 32, .framesPerSecond = 0}, ErrorKind::InvalidArgument);
  expectRefused(dir / "clip.mp4", {.width = 32, .height = 32, .audioSamples = tone, .audioSampleRate = 0}, ErrorKind::InvalidArgument);
  expectRefused(dir / "no_such_folder" / "clip.webm", {.width = 32, .height = 32}, ErrorKind::Io);
  const std::vector<float> overLimit(size_t(8000 * (audio::kMaxSoundtrackSeconds + 1)), 0.0f);
  expectRefused(dir / "long.mp4", {.width = 32, .height = 32, .audioSamples = overLimit, .audioSampleRate = 8000}, ErrorKind::TooLarge);

  auto writer = audio::VideoWriter::create(dir / "clip.mp4", {.width = 32, .height = 32});
  ASSERT_TRUE(writer.ok()) << writer.error().message;
  auto wrongSize = writer->addFrame(std::vector<uint8_t>(10));
  ASSERT_FALSE(wrongSize.ok());
  EXPECT_EQ(wrongSize.error().kind, ErrorKind::InvalidArgument);
  ASSERT_TRUE(writer->addFrame(gradientFrame(32, 32, 0)).ok());
  ASSERT_TRUE(writer->finish().ok());
  EXPECT_FALSE(writer->addFrame(gradientFrame(32, 32, 1)).ok());  // after finish()
}

}  // namespace
