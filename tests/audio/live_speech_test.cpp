// The live Speak model (audio/live_speech.h) and the step it shares with
// `facial say` (audio/spoken_line.h): a typed line becomes a voice and a
// viseme track; a face following the silent player's clock opens and closes
// its mouth while the line plays and rests when it ends or is stopped.
#include "audio/live_speech.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "facial/character.h"
#include "facial/runtime/rig/arkit_names.h"
#include "tests/common/test_support.h"

namespace {

std::vector<std::string> arkitFace() {
  std::vector<std::string> names;
  for (std::string_view n : facial::arkitBlendShapeNames()) names.emplace_back(n);
  return names;
}

size_t targetIndex(const std::vector<std::string>& names, std::string_view name) {
  return size_t(std::find(names.begin(), names.end(), name) - names.begin());
}

facial::Character speakingFace(const std::vector<std::string>& names) {
  const auto data = testing_support::sourceDir() / "data";
  auto face = facial::Character::create(data / "graphs" / "tour.json", names,
                                        {.expressions = data / "expressions.json", .idleLife = false, .speaks = true});
  EXPECT_TRUE(face) << face.error().message;
  EXPECT_TRUE(face->setBool("autoplay", false));
  EXPECT_TRUE(face->update(0.0f));
  return std::move(*face);
}

TEST(SpokenLine, VoiceAndTrackShareOneClock) {
  auto line = audio::speakLine("Hello there.", {.language = "en"});
  ASSERT_TRUE(line) << line.error().message;
  EXPECT_EQ(line->sampleRate, 22050);
  EXPECT_GT(line->seconds(), 0.4);
  ASSERT_NE(line->track, nullptr);
  EXPECT_GT(line->track->keyCount(), 4u);
  // The mouth's last move ends with the voice (espeak's phoneme events carry sample positions).
  EXPECT_NEAR(line->track->endTime(), line->seconds(), 0.3);
  EXPECT_TRUE(std::all_of(line->samples.begin(), line->samples.end(), [](float s) { return s >= -1.0f && s <= 1.0f; }));
}

TEST(SpokenLine, VietnameseSpeaks) {
  auto line = audio::speakLine("Xin chào, đây là bản tin tối nay.", {.language = "vi"});
  ASSERT_TRUE(line) << line.error().message;
  EXPECT_GT(line->seconds(), 1.0);
  EXPECT_GT(line->track->keyCount(), 10u);
}

// Follows the live line frame by frame (10 ms frames on the silent player's
// wall clock) until it ends; returns the widest jaw seen.
float followToTheEnd(audio::LiveSpeech& live, facial::Character& face, const std::vector<std::string>& names) {
  float widest = 0.0f, lastTime = -1.0f;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    const std::optional<float> time = live.update();
    if (!time) {
      if (face.speaking()) face.stopSpeaking();
      break;
    }
    EXPECT_GE(*time, lastTime) << "the audio clock never runs backwards";
    lastTime = *time;
    EXPECT_TRUE(face.setSpeechTime(*time));
    EXPECT_TRUE(face.update(0.01f));
    widest = std::max(widest, face.weights()[targetIndex(names, "jawOpen")]);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return widest;
}

TEST(LiveSpeech, TheMouthFollowsTheLineAndRestsAfterIt) {
  const std::vector<std::string> names = arkitFace();
  facial::Character face = speakingFace(names);
  const float restJaw = face.weights()[targetIndex(names, "jawOpen")];
  audio::LiveSpeech live({.silent = true});
  EXPECT_FALSE(live.update()) << "nothing plays before start()";
  auto track = live.start("Hello, how are you today?", "en");
  ASSERT_TRUE(track) << track.error().message;
  EXPECT_TRUE(live.speaking());
  EXPECT_EQ(live.text(), "Hello, how are you today?");
  EXPECT_EQ(live.describe().rfind("\"Hello, how are you today?\" (en, ", 0), 0u) << live.describe();
  EXPECT_EQ(live.takeNotes(), std::vector<std::string>{"sound off: silent player asked for (the face speaks silently)"});
  EXPECT_TRUE(live.takeNotes().empty()) << "the note is given once";
  ASSERT_TRUE(face.speak(*track));
  const double lineSeconds = live.lineSeconds();

  const auto started = std::chrono::steady_clock::now();
  const float widest = followToTheEnd(live, face, names);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_GT(widest, restJaw + 0.2f) << "the jaw opens on the vowels";
  EXPECT_GE(took, lineSeconds - 0.05) << "the line lasts as long as its voice, on the audio clock";
  EXPECT_FALSE(live.speaking());
  EXPECT_FALSE(face.speaking());
  ASSERT_TRUE(face.update(0.01f));
  EXPECT_NEAR(face.weights()[targetIndex(names, "jawOpen")], restJaw, 1e-4f) << "back to rest after the line";
}

TEST(LiveSpeech, SpeakingAgainReplacesTheLineAndStopEndsIt) {
  audio::LiveSpeech live({.silent = true});
  ASSERT_TRUE(live.start("This is a rather long first sentence that would take a few seconds.", "en"));
  const double firstSeconds = live.lineSeconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_GE(*live.update(), 0.25f);
  ASSERT_TRUE(live.start("Xin chào.", "vi"));
  EXPECT_EQ(live.text(), "Xin chào.");
  EXPECT_LT(live.lineSeconds(), firstSeconds);
  const std::optional<float> restarted = live.update();
  ASSERT_TRUE(restarted);
  EXPECT_LT(*restarted, 0.2f) << "the new line plays from its start";
  live.stop();
  EXPECT_FALSE(live.speaking());
  EXPECT_FALSE(live.update());
  EXPECT_EQ(live.track(), nullptr);
}

TEST(LiveSpeech, BadLinesAreRefusedInOneLineAndTheLinePlayingGoesOn) {
  audio::LiveSpeech live({.silent = true});
  ASSERT_TRUE(live.start("Still talking here for a little while.", "en"));
  auto blank = live.start("  \n\t", "en");
  ASSERT_FALSE(blank);
  EXPECT_EQ(blank.error().message, "speech: nothing to say: the text is empty");
  auto huge = live.start(std::string(audio::kMaxLiveCharacters + 1, 'a'), "en");
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("at most 2000"), std::string::npos) << huge.error().message;
  auto unknown = live.start("Hello", "xx-nowhere");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().message.rfind("speech: unknown language 'xx-nowhere'", 0), 0u) << unknown.error().message;
  EXPECT_EQ(unknown.error().message.find('\n'), std::string::npos) << unknown.error().message;
  EXPECT_TRUE(live.speaking());
  EXPECT_EQ(live.text(), "Still talking here for a little while.");
  EXPECT_TRUE(live.update());
}

}  // namespace
