// VisemeSampleJob: validity (what Validate refuses, Run leaving outputs
// alone), then results (cursor playback equals fresh sampling) and no allocation.
#include <gtest/gtest.h>

#include <limits>

#include "tests/common/allocation_counter.h"
#include "tests/facial/speech/speech_test_support.h"

using namespace facial;
using namespace facial::speech_test;

namespace {

const VisemeTrack& sampleTrack() {
  static const VisemeTrack track = buildOrDie(phonemeRun({{"h", 0.06f},
                                                          {"ə", 0.05f},
                                                          {"l", 0.07f},
                                                          {"oʊ", 0.25f},
                                                          {"_", 0.3f},
                                                          {"w", 0.06f},
                                                          {"ɜː", 0.15f},
                                                          {"l", 0.06f},
                                                          {"d", 0.08f},
                                                          {"m", 0.07f},
                                                          {"a", 0.2f}}));
  return track;
}

}  // namespace

TEST(VisemeSampleJobValidity, RefusesWhatDoesNotFitAndLeavesOutputsAlone) {
  std::array<uint32_t, kSpeechChannelCount> cursors{};
  std::array<uint32_t, 3> fewCursors{};
  std::array<float, kVisemeCount> visemes{};
  std::array<float, kVisemeCount - 1> fewVisemes{};
  std::array<float, kMouthChannelCount> mouth{};
  std::array<float, 2> badMouth{};
  const VisemeTrack* track = &sampleTrack();
  const VisemeTrack empty;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const VisemeSampleJob bad[] = {
      {.track = nullptr, .time = 0.1f, .cursors = cursors, .visemes = visemes, .mouth = mouth},
      {.track = &empty, .time = 0.1f, .cursors = cursors, .visemes = visemes, .mouth = mouth},
      {.track = track, .time = 0.1f, .cursors = fewCursors, .visemes = visemes, .mouth = mouth},
      {.track = track, .time = 0.1f, .cursors = cursors, .visemes = fewVisemes, .mouth = mouth},
      {.track = track, .time = 0.1f, .cursors = cursors, .visemes = visemes, .mouth = badMouth},
      {.track = track, .time = nan, .cursors = cursors, .visemes = visemes, .mouth = mouth},
      {.track = track,
       .time = std::numeric_limits<float>::infinity(),
       .cursors = cursors,
       .visemes = visemes,
       .mouth = mouth},
  };
  for (const VisemeSampleJob& job : bad) {
    visemes.fill(7.0f), fewVisemes.fill(7.0f), mouth.fill(7.0f);
    const auto valid = job.Validate();
    ASSERT_FALSE(valid);
    EXPECT_EQ(valid.error().kind, eng::ErrorKind::InvalidArgument);
    EXPECT_EQ(valid.error().message.rfind("VisemeSampleJob: ", 0), 0u) << valid.error().message;
    EXPECT_FALSE(job.Run());
    for (float w : visemes) EXPECT_EQ(w, 7.0f);
    for (float w : mouth) EXPECT_EQ(w, 7.0f);
  }
  EXPECT_TRUE((VisemeSampleJob{.track = track, .time = 0.1f, .cursors = cursors, .visemes = visemes}.Validate()))
      << "the mouth channels are optional";
}

TEST(VisemeSampleJob, PlaybackWithCursorsEqualsSamplingAfresh) {
  const VisemeTrack& track = sampleTrack();
  std::array<uint32_t, kSpeechChannelCount> cursors{};
  Frame played;
  // Forward at 60 Hz, then a seek back, then forward again.
  std::vector<float> times;
  for (float t = -0.2f; t < 1.8f; t += 1.0f / 60.0f) times.push_back(t);
  times.push_back(0.3f);
  for (float t = 0.31f; t < 0.9f; t += 1.0f / 60.0f) times.push_back(t);
  for (float t : times) {
    ASSERT_TRUE((VisemeSampleJob{
        .track = &track, .time = t, .cursors = cursors, .visemes = played.visemes, .mouth = played.mouth}
                     .Run()));
    const Frame fresh = sampleAt(track, t);
    for (size_t v = 0; v < kVisemeCount; ++v) ASSERT_FLOAT_EQ(played.visemes[v], fresh.visemes[v]) << "t = " << t;
    for (size_t c = 0; c < kMouthChannelCount; ++c) ASSERT_FLOAT_EQ(played.mouth[c], fresh.mouth[c]) << "t = " << t;
  }
}

TEST(VisemeSampleJob, SamplesTheKeysItWasBuiltFrom) {
  const VisemeTrack& track = sampleTrack();
  const auto jaw = track.mouthKeys(MouthChannel::JawOpen);
  ASSERT_GE(jaw.size(), 3u);
  const Keyframe& k = jaw[jaw.size() / 2];
  EXPECT_FLOAT_EQ(sampleAt(track, k.time)[MouthChannel::JawOpen], k.value);
  const auto m = track.visemeKeys(Viseme::PP);
  EXPECT_GT(sampleAt(track, 1.115f)[Viseme::PP], 0.99f) << "the m of \"world ma\"";
  EXPECT_GE(m.size(), 3u);
}

TEST(VisemeSampleJob, RunAllocatesNothing) {
  const VisemeTrack& track = sampleTrack();
  std::array<uint32_t, kSpeechChannelCount> cursors{};
  std::array<float, kVisemeCount> visemes{};
  std::array<float, kMouthChannelCount> mouth{};
  bool allRan = true;
  const uint64_t before = testing_support::allocationCount();
  for (int frame = 0; frame < 2000; ++frame)
    allRan &=
        VisemeSampleJob{
            .track = &track, .time = -0.5f + frame * 0.001f, .cursors = cursors, .visemes = visemes, .mouth = mouth}
            .Run();
  allRan &= VisemeSampleJob{.track = &track, .time = 0.2f, .cursors = cursors, .visemes = visemes, .mouth = mouth}
                .Run();  // a seek back
  EXPECT_EQ(testing_support::allocationCount() - before, 0u);
  EXPECT_TRUE(allRan);
  // The counter does count: a refused job's message allocates.
  const uint64_t beforeFailure = testing_support::allocationCount();
  EXPECT_FALSE((VisemeSampleJob{.track = nullptr, .cursors = cursors, .visemes = visemes}.Validate()));
  EXPECT_GT(testing_support::allocationCount() - beforeFailure, 0u);
}
