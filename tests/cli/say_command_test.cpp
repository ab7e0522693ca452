// `facial say`: a sentence, a presenter script, Rhubarb cues, a recording with
// its transcript or a bare recording spoken by a face into a video with its
// sound; the frames follow the viseme track (lips shut on PP, open on aa) and
// the emotions (their intensity, their changes mid-line); refused input exits
// non-zero with one line and no video.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

extern "C" {
#include <libavformat/avformat.h>
}

#include "app/presenter_script.h"
#include "audio/audio_file.h"
#include "engine/scene/gltf_writer.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

namespace fs = std::filesystem;

constexpr int kFps = 12;
// Bilabials and open vowels, about 1.5 s in espeak-ng's English.
constexpr const char* kSentence = "Bob, my papa, parked a car.";

struct StreamFacts {
  bool video = false, audio = false;
  double durationSeconds = 0;
};

StreamFacts reopen(const fs::path& path) {
  AVFormatContext* input = nullptr;
  if (avformat_open_input(&input, path.c_str(), nullptr, nullptr) < 0) return {};
  StreamFacts facts;
  if (avformat_find_stream_info(input, nullptr) >= 0) {
    facts.video = av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0) >= 0;
    facts.audio = av_find_best_stream(input, AVMEDIA_TYPE_AUDIO, -1, -1, nullptr, 0) >= 0;
    facts.durationSeconds = input->duration / double(AV_TIME_BASE);
  }
  avformat_close_input(&input);
  return facts;
}

// A mono 16-bit WAV of `seconds` of a tone pulsed four times a second (syllable-like bursts).
fs::path writePulsedTone(const fs::path& path, double seconds) {
  constexpr int rate = 16000;
  std::vector<int16_t> samples(size_t(seconds * rate));
  for (size_t i = 0; i < samples.size(); ++i) {
    const double t = double(i) / rate;
    const double gate = std::fmod(t, 0.25) < 0.15 ? 1.0 : 0.0;
    samples[i] = int16_t(12000 * gate * std::sin(2 * M_PI * 220 * t));
  }
  std::ofstream out(path, std::ios::binary);
  auto put = [&](uint32_t value, int bytes) { out.write(reinterpret_cast<const char*>(&value), bytes); };
  const uint32_t dataBytes = uint32_t(samples.size() * 2);
  out.write("RIFF", 4), put(36 + dataBytes, 4), out.write("WAVEfmt ", 8), put(16, 4), put(1, 2), put(1, 2);
  put(rate, 4), put(rate * 2, 4), put(2, 2), put(16, 2), out.write("data", 4), put(dataBytes, 4);
  out.write(reinterpret_cast<const char*>(samples.data()), dataBytes);
  return path;
}

// The middle of the longest cue of `viseme` in the --visemes JSON, as a frame index (-1: none).
int frameOnViseme(const nlohmann::json& cues, const std::string& viseme) {
  double longest = 0, middle = -1;
  for (const auto& cue : cues["visemes"])
    if (cue["viseme"] == viseme && double(cue["end"]) - double(cue["start"]) > longest) {
      longest = double(cue["end"]) - double(cue["start"]);
      middle = 0.5 * (double(cue["start"]) + double(cue["end"]));
    }
  return middle < 0 ? -1 : int(std::lround(middle * kFps));
}

// Dark pixels in the lower middle of the frame, where the head's mouth is: an open mouth is dark inside.
size_t darkMouthPixels(const eng::Image& image) {
  size_t dark = 0;
  for (int y = image.height * 55 / 100; y < image.height * 85 / 100; ++y)
    for (int x = image.width * 35 / 100; x < image.width * 65 / 100; ++x) {
      const uint8_t* p = &image.rgba8[(size_t(y) * image.width + x) * 4];
      if (0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] < 60) ++dark;
    }
  return dark;
}

class SayCommand : public ::testing::Test {
 protected:
  // One sentence rendered once for the suite (the slow part), with frames and the track.
  static void SetUpTestSuite() {
    sentenceDir_ = testing_support::freshTempDir("say_command_sentence");
    // At high quality: the dark-pixel counts below were measured with 4x multisampling (say's
    // default, auto, is balanced and so 1x on lavapipe, where an aliased lip line at 128 px doubles them).
    sentenceRun_ = runFacial({"say", kSentence, "--size", "128x128", "--quality", "high", "--fps", std::to_string(kFps),
                              "--out", (sentenceDir_ / "talk.mp4").string(), "--frames", (sentenceDir_ / "frames").string(),
                              "--visemes", (sentenceDir_ / "visemes.json").string(), "--wav",
                              (sentenceDir_ / "talk.wav").string()});
  }
  void SetUp() override { dir_ = testing_support::freshTempDir("say_command"); }

  // Runs `say` with `args` expecting a one-line refusal containing `expected`, and no video left behind.
  void expectRefused(std::vector<std::string> args, const std::string& expected) {
    const fs::path out = dir_ / "refused.mp4";
    args.insert(args.begin(), "say");
    args.insert(args.end(), {"--size", "64x64", "--out", out.string()});
    const CommandOutput run = runFacial(args);
    EXPECT_NE(run.exitCode, 0) << expected;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_EQ(countOccurrences(run.err, "\n"), 1u) << run.err;
    EXPECT_FALSE(fs::exists(out)) << expected;
    EXPECT_FALSE(fs::exists(out.string() + ".partial")) << expected;
  }

  // The first and last frames of `say` with `args` at 64x64, 10 fps.
  std::pair<eng::Image, eng::Image> firstAndLastFrames(std::vector<std::string> args, const std::string& name) {
    const fs::path frames = dir_ / name;
    args.insert(args.begin(), "say");
    args.insert(args.end(), {"--size", "64x64", "--fps", "10", "--out", (dir_ / (name + ".mp4")).string(),
                             "--frames", frames.string()});
    const CommandOutput run = runFacial(args);
    EXPECT_TRUE(ranCleanly(run)) << name;
    const size_t count = std::distance(fs::directory_iterator(frames), fs::directory_iterator());
    char last[32];
    std::snprintf(last, sizeof last, "frame_%04zu.png", count - 1);
    return {readPngOrFail(frames / "frame_0000.png"), readPngOrFail(frames / last)};
  }

  static inline fs::path sentenceDir_;
  static inline CommandOutput sentenceRun_;
  fs::path dir_;
};

TEST_F(SayCommand, SentenceBecomesAVideoWithSound) {
  ASSERT_TRUE(ranCleanly(sentenceRun_));
  const StreamFacts facts = reopen(sentenceDir_ / "talk.mp4");
  EXPECT_TRUE(facts.video);
  EXPECT_TRUE(facts.audio);
  // The sentence lasts about 1.5 s, plus the 0.2 s rest at the end.
  EXPECT_GT(facts.durationSeconds, 1.0);
  EXPECT_LT(facts.durationSeconds, 3.0);
  const size_t frames = std::distance(fs::directory_iterator(sentenceDir_ / "frames"), fs::directory_iterator());
  EXPECT_NEAR(double(frames) / kFps, facts.durationSeconds, 0.25);
}

TEST_F(SayCommand, WavIsTheVideosSoundtrack) {
  ASSERT_TRUE(ranCleanly(sentenceRun_));
  EXPECT_EQ(testing_support::partialFilesIn(sentenceDir_), 0u);
  auto clip = audio::readAudioFile(sentenceDir_ / "talk.wav");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  EXPECT_EQ(clip->sampleRate, 22050);  // espeak-ng's
  // The soundtrack is padded with silence to the video's length (the 0.2 s rest at the end).
  EXPECT_NEAR(clip->durationSeconds(), reopen(sentenceDir_ / "talk.mp4").durationSeconds, 0.1);
}

TEST_F(SayCommand, RecordingWithItsTranscriptIsAligned) {
  ASSERT_TRUE(ranCleanly(sentenceRun_));
  const CommandOutput run = runFacial({"say", "--audio", (sentenceDir_ / "talk.wav").string(), "--text", kSentence,
                                       "--size", "64x64", "--fps", "8", "--out", (dir_ / "aligned.mp4").string(),
                                       "--visemes", (dir_ / "aligned.json").string()});
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_EQ(run.err.find("note:"), std::string::npos) << run.err;
  std::ifstream in(dir_ / "aligned.json");
  const nlohmann::json cues = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(cues.is_object());
  // The phonemes came from the transcript: the bilabials of "Bob, my papa" close the lips.
  int bilabials = 0;
  for (const auto& cue : cues["visemes"]) bilabials += cue["viseme"] == "PP";
  EXPECT_GE(bilabials, 4) << cues.dump();
}

TEST_F(SayCommand, TranscriptThatCannotBeAlignedFallsBackToTheSyllables) {
  const CommandOutput run = runFacial({"say", "--audio", writePulsedTone(dir_ / "tone.wav", 1.0).string(), "--text",
                                       "zzqxvw blorf", "--size", "64x64", "--fps", "8", "--out",
                                       (dir_ / "fallback.mp4").string()});
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_EQ(countOccurrences(run.err, "facial say: note: --text not aligned to"), 1u) << run.err;
  EXPECT_NE(run.err.find("the mouth follows its syllables instead"), std::string::npos) << run.err;
  EXPECT_TRUE(reopen(dir_ / "fallback.mp4").audio);
}

TEST_F(SayCommand, IntensityScalesTheEmotion) {
  const auto neutral = firstAndLastFrames({"Mmm.", "--emotion", "neutral"}, "neutral");
  const auto happy = firstAndLastFrames({"Mmm.", "--emotion", "happy"}, "happy");
  const auto faint = firstAndLastFrames({"Mmm.", "--emotion", "happy", "--intensity", "0.1"}, "faint");
  const double faintToNeutral = differingFraction(faint.first, neutral.first);
  const double faintToHappy = differingFraction(faint.first, happy.first);
  EXPECT_LT(faintToNeutral, faintToHappy) << faintToNeutral << " vs " << faintToHappy;
  // The first frame is already speech's "m" (lips closed): happy differs in the smile's corners, cheeks and eyes.
  EXPECT_GT(differingFraction(neutral.first, happy.first), 0.01);
}

TEST_F(SayCommand, ScriptSwitchesTheEmotionMidLine) {
  const auto happy = firstAndLastFrames({"Mmm.", "--emotion", "happy"}, "happy");
  const auto sad = firstAndLastFrames({"Mmm.", "--emotion", "sad"}, "sad");
  std::ofstream(dir_ / "bulletin.txt") << "# two emotions in one line\n[happy] Mmm, mmm. [sad] Mmm, mmm, mmm.\n";
  const fs::path frames = dir_ / "script";
  const CommandOutput run = runFacial({"say", "--script", (dir_ / "bulletin.txt").string(), "--size", "64x64",
                                       "--fps", "10", "--out", (dir_ / "bulletin.mp4").string(), "--frames",
                                       frames.string()});
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_NE(run.out.find("(happy > sad)"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("say: 100%"), std::string::npos) << run.err;  // the progress
  const StreamFacts facts = reopen(dir_ / "bulletin.mp4");
  EXPECT_TRUE(facts.video && facts.audio);
  const size_t count = std::distance(fs::directory_iterator(frames), fs::directory_iterator());
  char lastName[32];
  std::snprintf(lastName, sizeof lastName, "frame_%04zu.png", count - 1);
  const eng::Image first = readPngOrFail(frames / "frame_0000.png");
  const eng::Image last = readPngOrFail(frames / lastName);
  EXPECT_LT(differingFraction(first, happy.first), differingFraction(first, sad.first));
  EXPECT_LT(differingFraction(last, sad.second), differingFraction(last, happy.second));
}

TEST_F(SayCommand, MalformedScriptIsRefusedWithItsLine) {
  const fs::path script = dir_ / "bulletin.txt";
  std::ofstream(script) << "Good evening.\n[bored] Here is the news.\n";
  expectRefused({"--script", script.string()}, "bulletin.txt:2: unknown tag '[bored]'");
  std::ofstream(script) << "Good evening [pause soon].\n";
  expectRefused({"--script", script.string()}, "bulletin.txt:1: pause 'soon'");
  std::ofstream(script) << "\n\nGood [happy evening.\n";
  expectRefused({"--script", script.string()}, "bulletin.txt:3: '[' is not closed");
  std::ofstream(script) << "# nothing\n";
  expectRefused({"--script", script.string()}, "says nothing");
  std::ofstream(script) << std::string(app::kMaxPresenterScriptBytes + 1, 'a');
  expectRefused({"--script", script.string()}, "over the script limit of 1 MB");
  expectRefused({"--script", script.string(), "hello"}, "give no TEXT, --audio or --cues");
  expectRefused({"--script", (dir_ / "absent.txt").string()}, "absent.txt: cannot open the script");
}

TEST_F(SayCommand, LipsCloseOnPPAndOpenOnAa) {
  ASSERT_TRUE(ranCleanly(sentenceRun_));
  std::ifstream in(sentenceDir_ / "visemes.json");
  const nlohmann::json cues = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(cues.is_object());
  const int closed = frameOnViseme(cues, "PP");
  const int open = frameOnViseme(cues, "aa");
  ASSERT_GE(closed, 0);
  ASSERT_GE(open, 0);
  char closedName[32], openName[32];
  std::snprintf(closedName, sizeof closedName, "frame_%04d.png", closed);
  std::snprintf(openName, sizeof openName, "frame_%04d.png", open);
  const size_t closedDark = darkMouthPixels(readPngOrFail(sentenceDir_ / "frames" / closedName));
  const size_t openDark = darkMouthPixels(readPngOrFail(sentenceDir_ / "frames" / openName));
  // At 128 px about 16 dark pixels with the lips shut (the lip line), 50-80 on an open vowel.
  EXPECT_GT(openDark, 2 * closedDark + 10) << closedDark << " dark on PP frame " << closed << ", " << openDark
                                           << " dark on aa frame " << open;
}

TEST_F(SayCommand, RhubarbCuesDriveTheFaceOverTheirRecording) {
  FACIAL_REQUIRE_SHARED();
  const fs::path speech = testing_support::sharedDir() / "speech";
  const fs::path out = dir_ / "bonjour.webm";
  const CommandOutput run = runFacial({"say", "--cues", (speech / "bonjour.json").string(), "--audio",
                                       (speech / "bonjour.ogg").string(), "--size", "64x64", "--fps", "8", "--out",
                                       out.string()});
  ASSERT_TRUE(ranCleanly(run));
  const StreamFacts facts = reopen(out);
  EXPECT_TRUE(facts.video);
  EXPECT_TRUE(facts.audio);
}

TEST_F(SayCommand, RecordingAloneMovesTheMouth) {
  const fs::path out = dir_ / "tone.mp4";
  const CommandOutput run = runFacial({"say", "--audio", writePulsedTone(dir_ / "tone.wav", 1.0).string(),
                                       "--size", "64x64", "--fps", "8", "--out", out.string(), "--visemes",
                                       (dir_ / "tone.json").string()});
  ASSERT_TRUE(ranCleanly(run));
  EXPECT_TRUE(reopen(out).audio);
  std::ifstream in(dir_ / "tone.json");
  const nlohmann::json cues = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(cues.is_object());
  bool opened = false;
  for (const auto& cue : cues["visemes"]) opened = opened || cue["viseme"] != "sil";
  EXPECT_TRUE(opened) << cues.dump();
}

TEST_F(SayCommand, BadInputIsRefusedInOneLineWithoutAVideo) {
  expectRefused({"   "}, "TEXT is empty");
  expectRefused({"hello", "--lang", "xx-nowhere"}, "unknown language 'xx-nowhere'");
  expectRefused({"hello", "--emotion", "bored"}, "--emotion 'bored'");
  expectRefused({"hello", "--intensity", "1.5"}, "--intensity must be a number in [0, 1]");
  expectRefused({"hello", "--intensity", "nan"}, "--intensity must be a number in [0, 1]");
  expectRefused({"hello", "--lod-error", "-1"}, "--lod-error must be a number of pixels in [0, 64]");
  expectRefused({"hello", "--lod-error", "nan"}, "--lod-error must be a number of pixels in [0, 64]");
  expectRefused({"hello", "--wav", (dir_ / "voice.mp3").string()}, "must end in .wav");
  expectRefused({"--audio", (dir_ / "missing.wav").string()}, "missing.wav");
  std::ofstream(dir_ / "corrupt.wav") << "RIFF not really a wave file";
  expectRefused({"--audio", (dir_ / "corrupt.wav").string()}, "corrupt.wav");
  const fs::path tone = writePulsedTone(dir_ / "tone.wav", 0.5);
  std::ofstream(dir_ / "bad_cues.json") << R"({"mouthCues": [{"start": 0.0, "end": 0.2, "value": "Z"}]})";
  expectRefused({"--cues", (dir_ / "bad_cues.json").string(), "--audio", tone.string()}, "bad_cues.json");
}

TEST_F(SayCommand, FaceThatCannotSpeakIsRefused) {
  // The test face with its targets renamed to brow and lip-corner units: it
  // emotes (so it is not rigged on the fly), but nothing opens or shapes the mouth.
  eng::Model face = makeTestFace();
  for (auto& mesh : face.meshes)
    mesh.targetNames = {"AU1_InnerBrowRaiser", "AU4_BrowLowerer", "AU12_LipCornerPuller_L", "AU15_LipCornerDepressor",
                        "custom_shape"};
  const fs::path model = dir_ / "mute_face.glb";
  ASSERT_TRUE(eng::saveModel(face, model));
  expectRefused({"hello", "--model", model.string()}, "cannot speak");
}

}  // namespace
}  // namespace cli_test
