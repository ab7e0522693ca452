// `facial say`'s picture against its sound, from the rendered frames and the
// video's decoded audio: the mouth opens as the voice gets loud (the lag of
// best correlation within one frame), rests in the silences, and shuts on
// every p, b and m the --visemes track names.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

namespace cli_test::say_sync {  // its own: the tests build several to a unit
namespace {

namespace fs = std::filesystem;

constexpr double kFps = 25;
// Bilabials between open vowels, with a comma's pause: about 2.2 s in espeak-ng's English.
constexpr const char* kSentence = "Bob, my papa, parked a car.";
// Lags tried, in frames (a syllable lasts 4-6).
constexpr int kMaxLag = 6;

// One value per video frame k: the RMS of the samples within half a frame of k / fps.
struct AudioEnvelope {
  std::vector<double> sumSquares, count;
  void add(double t, double x) {
    if (t < -0.5 / kFps) return;
    const size_t k = size_t(std::lround(t * kFps));
    if (k >= sumSquares.size()) sumSquares.resize(k + 1), count.resize(k + 1);
    sumSquares[k] += x * x;
    count[k] += 1;
  }
  std::vector<double> rms(size_t frames) const {
    std::vector<double> out(frames, 0.0);
    for (size_t k = 0; k < std::min(frames, count.size()); ++k)
      if (count[k] > 0) out[k] = std::sqrt(sumSquares[k] / count[k]);
    return out;
  }
};

void addDecoded(AVCodecContext* decoder, AVFrame* frame, AVRational timeBase, AudioEnvelope& envelope) {
  while (avcodec_receive_frame(decoder, frame) == 0) {
    const double start = frame->best_effort_timestamp * av_q2d(timeBase);
    const auto format = AVSampleFormat(frame->format);
    for (int i = 0; i < frame->nb_samples; ++i) {
      double x = 0;
      if (format == AV_SAMPLE_FMT_FLTP || format == AV_SAMPLE_FMT_FLT) x = reinterpret_cast<const float*>(frame->data[0])[i];
      else if (format == AV_SAMPLE_FMT_S16P || format == AV_SAMPLE_FMT_S16) x = reinterpret_cast<const int16_t*>(frame->data[0])[i] / 32768.0;
      envelope.add(start + double(i) / frame->sample_rate, x);
    }
  }
}

// The video's sound as heard, placed by its timestamps (the muxer's edit list and the encoder's delay applied).
AudioEnvelope decodeAudio(const fs::path& video) {
  AudioEnvelope envelope;
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, video.c_str(), nullptr, nullptr) < 0) return envelope;
  const AVCodec* codec = nullptr;
  const int stream = avformat_find_stream_info(input, nullptr) >= 0
                         ? av_find_best_stream(input, AVMEDIA_TYPE_AUDIO, -1, -1, &codec, 0) : -1;
  AVCodecContext* decoder = stream >= 0 ? avcodec_alloc_context3(codec) : nullptr;
  if (decoder && avcodec_parameters_to_context(decoder, input->streams[stream]->codecpar) >= 0 &&
      avcodec_open2(decoder, codec, nullptr) >= 0) {
    const AVRational timeBase = input->streams[stream]->time_base;
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    while (av_read_frame(input, packet) >= 0) {
      if (packet->stream_index == stream && avcodec_send_packet(decoder, packet) == 0)
        addDecoded(decoder, frame, timeBase, envelope);
      av_packet_unref(packet);
    }
    if (avcodec_send_packet(decoder, nullptr) == 0) addDecoded(decoder, frame, timeBase, envelope);
    av_frame_free(&frame);
    av_packet_free(&packet);
  }
  avcodec_free_context(&decoder);
  avformat_close_input(&input);
  return envelope;
}

// How far the mouth moved from `rest`: pixels of the lower face (around the mouth of a face-framed
// head) that differ in some channel by more than 24.
double mouthMotion(const eng::Image& frame, const eng::Image& rest) {
  if (frame.width != rest.width || frame.height != rest.height || frame.rgba8.size() != rest.rgba8.size()) return -1;
  size_t moved = 0;
  for (int y = frame.height * 55 / 100; y < frame.height * 85 / 100; ++y)
    for (int x = frame.width * 30 / 100; x < frame.width * 70 / 100; ++x) {
      const size_t i = (size_t(y) * frame.width + x) * 4;
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(frame.rgba8[i + c]) - int(rest.rgba8[i + c])) > 24) {
          ++moved;
          break;
        }
    }
  return double(moved);
}

// Pearson correlation of mouth[k] with audio[k + lag] over the frames both have.
double correlation(const std::vector<double>& mouth, const std::vector<double>& audio, int lag) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int k = 0; k < int(mouth.size()); ++k) {
    const int j = k + lag;
    if (j < 0 || j >= int(audio.size())) continue;
    sa += mouth[k], sb += audio[j], saa += mouth[k] * mouth[k], sbb += audio[j] * audio[j], sab += mouth[k] * audio[j];
    n += 1;
  }
  const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : 0;
}

fs::path framePath(const fs::path& dir, size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04zu.png", index);
  return dir / name;
}

class SaySync : public ::testing::Test {
 protected:
  // One sentence rendered once (the slow part): the video, its frames and the viseme track.
  static void SetUpTestSuite() {
    dir_ = testing_support::freshTempDir("say_sync");
    run_ = runFacial({"say", kSentence, "--size", "256x256", "--fps", "25", "--out", (dir_ / "talk.mp4").string(),
                      "--frames", (dir_ / "frames").string(), "--visemes", (dir_ / "visemes.json").string()});
    if (run_.exitCode != 0) return;
    const size_t frames = std::distance(fs::directory_iterator(dir_ / "frames"), fs::directory_iterator());
    if (frames < 10) return;
    // The last frame is the rest pose: the clip ends 0.2 s after the track, the mouth settled.
    const eng::Image rest = readPngOrFail(framePath(dir_ / "frames", frames - 1));
    for (size_t k = 0; k < frames; ++k) mouth_.push_back(mouthMotion(readPngOrFail(framePath(dir_ / "frames", k)), rest));
    audio_ = decodeAudio(dir_ / "talk.mp4").rms(frames);
  }

  void SetUp() override {
    ASSERT_TRUE(ranCleanly(run_));
    ASSERT_GE(mouth_.size(), 40u) << "a 2 s sentence at 25 fps";
    widest_ = *std::max_element(mouth_.begin(), mouth_.end());
    loudest_ = *std::max_element(audio_.begin(), audio_.end());
    // Open vowels move hundreds of pixels at 256x256; a face that never opens its mouth fails here.
    ASSERT_GT(widest_, 500) << "the mouth barely moved";
    ASSERT_GT(loudest_, 0.05) << "the video's sound is silent";
  }

  // At rest: within a tenth of the widest opening from the final rest pose.
  bool closed(size_t k) const { return mouth_[k] <= 0.1 * widest_; }

  static inline fs::path dir_;
  static inline CommandOutput run_;
  static inline std::vector<double> mouth_, audio_;
  double widest_ = 0, loudest_ = 0;
};

TEST_F(SaySync, MouthFollowsTheVoiceWithinOneFrame) {
  int bestLag = 0;
  double best = -2;
  std::string all;
  for (int lag = -kMaxLag; lag <= kMaxLag; ++lag) {
    const double c = correlation(mouth_, audio_, lag);
    all += std::to_string(lag) + ":" + std::to_string(c).substr(0, 5) + " ";
    if (c > best) best = c, bestLag = lag;
  }
  EXPECT_LE(std::abs(bestLag), 1) << "lag (frames, + = mouth ahead of the sound) to correlation: " << all;
  EXPECT_GT(best, 0.5) << all;  // speech loudness and mouth opening go together
}

TEST_F(SaySync, MouthRestsInSilence) {
  EXPECT_TRUE(closed(0)) << "first frame moved " << mouth_[0] << " of " << widest_;
  // Silent frames two frames away from any sound (the mouth opens a little ahead of it and closes after).
  const double quiet = 0.1 * loudest_;
  size_t checked = 0;
  for (size_t k = 2; k + 2 < mouth_.size(); ++k) {
    if (std::any_of(audio_.begin() + k - 2, audio_.begin() + k + 3, [&](double a) { return a >= quiet; })) continue;
    ++checked;
    EXPECT_TRUE(closed(k)) << "frame " << k << " is silent but the mouth moved " << mouth_[k] << " of " << widest_;
  }
  // The comma's pause and the end: at least the 0.2 s tail.
  EXPECT_GE(checked, 5u);
}

TEST_F(SaySync, LipsShutOnEveryBilabial) {
  std::ifstream in(dir_ / "visemes.json");
  const nlohmann::json track = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(track.is_object() && track.contains("visemes"));
  size_t checked = 0;
  for (const auto& cue : track["visemes"]) {
    const double start = cue["start"], end = cue["end"];
    if (cue["viseme"] != "PP" || end - start < 1 / kFps) continue;  // shorter ones may fall between frames
    const size_t k = size_t(std::floor(0.5 * (start + end) * kFps));  // the frame whose interval holds the middle
    if (k >= mouth_.size()) continue;
    ++checked;
    EXPECT_TRUE(closed(k)) << "PP " << start << "-" << end << " s: frame " << k << " moved " << mouth_[k] << " of "
                           << widest_;
  }
  EXPECT_GE(checked, 4u) << "Bob, papa, parked: b, p, p, p";
}

}  // namespace
}  // namespace cli_test::say_sync
