#include "audio/player.h"

#include <gtest/gtest.h>

#include <thread>

#include "tests/audio/speech_samples.h"

namespace {

TEST(Player, SilentPlayerSaysSoundIsOff) {
  audio::Player player = audio::Player::open({.silent = true});
  EXPECT_FALSE(player.hasSound());
  EXPECT_EQ(player.note().rfind("sound off: ", 0), 0u) << player.note();
  EXPECT_EQ(player.note().find('\n'), std::string::npos);
  EXPECT_EQ(player.clockSeconds(), 0.0);  // nothing played yet
  EXPECT_TRUE(player.finished());
}

TEST(Player, SilentClockRunsToTheEndOfTheClipAndStops) {
  audio::Player player = audio::Player::open({.silent = true});
  const std::vector<float> clip(80, 0.0f);  // 10 ms at 8 kHz
  ASSERT_TRUE(player.play(clip, 8000).ok());
  const double early = player.clockSeconds();
  EXPECT_GE(early, 0.0);
  EXPECT_LE(early, 0.010);
  // sleep_for waits at least this long: the clock has run past the clip, and stays at its end.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_DOUBLE_EQ(player.clockSeconds(), 0.010);
  EXPECT_TRUE(player.finished());
}

TEST(Player, StopFreezesTheClockAndPlayRestartsIt) {
  audio::Player player = audio::Player::open({.silent = true});
  const std::vector<float> clip(8000 * 60, 0.0f);  // a minute
  ASSERT_TRUE(player.play(clip, 8000).ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_FALSE(player.finished());
  player.stop();
  const double stoppedAt = player.clockSeconds();
  EXPECT_GE(stoppedAt, 0.005);
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(player.clockSeconds(), stoppedAt);
  EXPECT_TRUE(player.finished());
  ASSERT_TRUE(player.play(clip, 8000).ok());
  EXPECT_FALSE(player.finished());  // a minute to go again
}

TEST(Player, RefusesBadClips) {
  audio::Player player = audio::Player::open({.silent = true});
  const std::vector<float> clip(100, 0.0f);
  EXPECT_FALSE(player.play({}, 8000).ok());
  EXPECT_FALSE(player.play(clip, 0).ok());
  EXPECT_FALSE(player.play(clip, 1000000).ok());
  auto tooLong = player.play(std::vector<float>(8000 * 60 * 31, 0.0f), 8000);
  ASSERT_FALSE(tooLong.ok());
  EXPECT_EQ(tooLong.error().kind, eng::ErrorKind::TooLarge);
}

// Through the sound card, when this machine has one; CI and ssh sessions do not.
TEST(Player, SoundCardClockFollowsTheAudio) {
  audio::Player player = audio::Player::open();
  if (!player.hasSound()) GTEST_SKIP() << player.note();
  const std::vector<float> clip = audio_test::tone(440, 0.3, 44100, 0.1f);
  ASSERT_TRUE(player.play(clip, 44100).ok());
  if (!player.hasSound()) GTEST_SKIP() << player.note();
  double previous = 0;
  for (int poll = 0; poll < 500 && !player.finished(); ++poll) {  // 5 s at most: a stalled device fails below
    const double now = player.clockSeconds();
    EXPECT_GE(now, previous);
    EXPECT_LE(now, 0.3);
    previous = now;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(player.finished()) << "the sound card's clock stopped at " << player.clockSeconds() << " s";
  EXPECT_DOUBLE_EQ(player.clockSeconds(), 0.3);
}

}  // namespace
