#include "facial/runtime/graph/timeline_json.h"

#include <gtest/gtest.h>

#include "facial/runtime/graph/curve_json.h"
#include "tests/common/test_support.h"

using namespace facial;

namespace {

std::filesystem::path writeTimeline(const std::string& name, const std::string& text) {
  const auto path = testing_support::freshTempDir("timeline_json_" + name) / (name + ".json");
  testing_support::writeFile(path, text);
  return path;
}

std::string loadError(const std::string& name, const std::string& text) {
  auto t = loadTimeline(writeTimeline(name, text));
  EXPECT_FALSE(t.ok()) << name << " loaded";
  return t.ok() ? std::string() : t.error().message;
}

}  // namespace

TEST(TimelineJson, ReadsTracksKeysAndDefaults) {
  auto t = loadTimeline(writeTimeline("talk", R"({"version": 1, "loop": "pingpong", "tracks": [
      {"channel": "AU26_JawDrop", "interpolation": "cosine", "keys": [[0, 0], [0.25, 0.6],
        {"t": 0.5, "v": 0.1, "interp": "hermite", "out": -1}, [1.0, 0]]},
      {"channel": "AU25_LipsPart", "keys": [[0.2, 0.4]]}]})"));
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->name, "talk");  // from the file name
  EXPECT_FLOAT_EQ(t->duration, 1.0f);  // last key
  EXPECT_EQ(t->loop, LoopMode::PingPong);
  ASSERT_EQ(t->tracks.size(), 2u);
  const auto jaw = t->trackKeys(0);
  EXPECT_EQ(jaw[1].interpolation, KeyInterpolation::Cosine);
  EXPECT_EQ(jaw[2].interpolation, KeyInterpolation::Hermite);
  EXPECT_FLOAT_EQ(jaw[2].outTangent, -1.0f);
  EXPECT_EQ(t->trackKeys(1)[0].interpolation, KeyInterpolation::Linear);
}

TEST(TimelineJson, SaveThenLoadGivesTheSameTimeline) {
  Timeline t;
  t.name = "round";
  t.duration = 3.0f;
  t.loop = LoopMode::Loop;
  const std::vector<Keyframe> keys = {{0.0f, 0.1f, 0, 0, KeyInterpolation::Step},
                                      {1.1f, 0.7f, 0.5f, -0.25f, KeyInterpolation::Hermite},
                                      {2.9f, 0.3f, 0, 0, KeyInterpolation::Cosine}};
  t.addTrack("AU1_InnerBrowRaiser", keys);
  const auto path = testing_support::freshTempDir("timeline_json_round") / "round.json";
  ASSERT_TRUE(saveTimeline(t, path).ok());
  auto back = loadTimeline(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->name, "round");
  EXPECT_EQ(back->duration, 3.0f);
  EXPECT_EQ(back->loop, LoopMode::Loop);
  ASSERT_EQ(back->keys.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back->keys[i].time, keys[i].time);
    EXPECT_EQ(back->keys[i].value, keys[i].value);
    EXPECT_EQ(back->keys[i].inTangent, keys[i].inTangent);
    EXPECT_EQ(back->keys[i].outTangent, keys[i].outTangent);
    EXPECT_EQ(back->keys[i].interpolation, keys[i].interpolation);
  }
}

// The channels mark says what the track names stand for; unmarked files stay
// unmarked when written back (the player decides for them, as before).
TEST(TimelineJson, ChannelsMarkIsReadAndWrittenBack) {
  auto targets = loadTimeline(writeTimeline("targets", R"({"version": 1, "channels": "targets", "tracks": [
      {"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})"));
  ASSERT_TRUE(targets.ok()) << targets.error().message;
  EXPECT_EQ(targets->channels, TimelineChannels::Targets);
  EXPECT_EQ(timelineToJson(*targets).at("channels"), "targets");
  auto units = loadTimeline(writeTimeline("units", R"({"version": 1, "channels": "actionUnits", "tracks": [
      {"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})"));
  ASSERT_TRUE(units.ok()) << units.error().message;
  EXPECT_EQ(units->channels, TimelineChannels::ActionUnits);
  auto unmarked = loadTimeline(writeTimeline("unmarked", R"({"version": 1, "tracks": [
      {"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}]})"));
  ASSERT_TRUE(unmarked.ok()) << unmarked.error().message;
  EXPECT_EQ(unmarked->channels, TimelineChannels::Unmarked);
  EXPECT_FALSE(timelineToJson(*unmarked).contains("channels"));
}

TEST(TimelineJsonValidity, ChannelsMarkMustBeKnownAndTrue) {
  const std::string unknown = loadError("unknown_mark", R"({"version": 1, "channels": "weights", "tracks": [
      {"channel": "a", "keys": [[0, 0], [1, 1]]}]})");
  EXPECT_NE(unknown.find("unknown_mark.json: /channels: unknown channels 'weights' (expected actionUnits or targets)"),
            std::string::npos) << unknown;
  const std::string notUnit = loadError("not_unit", R"({"version": 1, "channels": "actionUnits", "tracks": [
      {"channel": "AU26_JawDrop", "keys": [[0, 0], [1, 1]]}, {"channel": "mouthSmile", "keys": [[0, 1]]}]})");
  EXPECT_NE(notUnit.find("not_unit.json: /tracks/1: channel 'mouthSmile' is not an action unit"), std::string::npos)
      << notUnit;
}

TEST(TimelineJsonValidity, ErrorsNameFilePointerAndProblem) {
  const std::string unsorted = loadError("unsorted", R"({"version": 1, "tracks": [
      {"channel": "a", "keys": [[0, 0], [1, 1]]},
      {"channel": "b", "keys": [[0, 0], [0.5, 1], [0.4, 0]]}]})");
  EXPECT_NE(unsorted.find("unsorted.json: /tracks/1/keys/2: key time"), std::string::npos) << unsorted;

  const std::string version = loadError("version", R"({"version": 2, "tracks": []})");
  EXPECT_NE(version.find("version.json: /version: unsupported version 2"), std::string::npos) << version;

  const std::string interp = loadError("interp", R"({"version": 1, "tracks": [
      {"channel": "a", "keys": [{"t": 0, "v": 0, "interp": "bouncy"}, [1, 1]]}]})");
  EXPECT_NE(interp.find("/tracks/0/keys/0/interp: unknown interpolation 'bouncy'"), std::string::npos) << interp;

  const std::string shortDuration = loadError("short", R"({"version": 1, "duration": 0.5, "tracks": [
      {"channel": "a", "keys": [[0, 0], [1, 1]]}]})");
  EXPECT_NE(shortDuration.find("/duration: duration 0.5"), std::string::npos) << shortDuration;

  const std::string typo = loadError("typo", R"({"version": 1, "tracks": [{"chanel": "a", "keys": [[0, 0]]}]})");
  EXPECT_NE(typo.find("/tracks/0/chanel: unknown key"), std::string::npos) << typo;

  const std::string twice = loadError("twice", R"({"version": 1, "tracks": [
      {"channel": "a", "keys": [[0, 0], [1, 1]]}, {"channel": "a", "keys": [[0, 1]]}]})");
  EXPECT_NE(twice.find("/tracks/1/channel: channel 'a' already has a track"), std::string::npos) << twice;

  const std::string nan = loadError("nan", R"({"version": 1, "tracks": [{"channel": "a", "keys": [[0, "x"]]}]})");
  EXPECT_NE(nan.find("/tracks/0/keys/0/1: expected a number, got string"), std::string::npos) << nan;

  const std::string deep = loadError("deep", R"({"version": 1, "tracks": [{"channel": "a", "keys": )" +
                                                 std::string(100000, '[') + std::string(100000, ']') + "}]}");
  EXPECT_NE(deep.find("deep.json: JSON nests 100003 levels deep, more than the 256 accepted"), std::string::npos) << deep;

  const std::string broken = loadError("broken", R"({"version": 1, "tracks": [)");
  EXPECT_NE(broken.find("broken.json: invalid JSON"), std::string::npos) << broken;

  auto missing = loadTimeline("/nonexistent/dir/none.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("none.json"), std::string::npos);
}

// The JSON forms without a file: the public readers return errors as values (the
// reader's internal exception never leaves them), the pointer relative to the value given.
TEST(TimelineJsonValidity, InMemoryReadersReturnErrorsNotExceptions) {
  const Json badKey = Json::parse(R"({"tracks": [{"channel": "a", "keys": [[0, 0], [1, "high"]]}]})");
  eng::Result<Timeline> timeline = eng::makeError(eng::ErrorKind::Io, "not read");
  EXPECT_NO_THROW(timeline = timelineFromJson(badKey, "inline"));
  ASSERT_FALSE(timeline.ok());
  EXPECT_EQ(timeline.error().kind, eng::ErrorKind::Malformed);
  EXPECT_EQ(timeline.error().message, "/tracks/0/keys/1/1: expected a number, got string");

  auto good = timelineFromJson(Json::parse(R"({"tracks": [{"channel": "a", "keys": [[0, 0], [1, 1]]}]})"), "inline");
  ASSERT_TRUE(good.ok()) << good.error().message;
  EXPECT_EQ(good->name, "inline");
  EXPECT_EQ(good->duration, 1.0f);

  auto keys = keyframesFromJson(Json::parse("[[0, 0], [0, 1]]"), KeyInterpolation::Linear);
  ASSERT_FALSE(keys.ok());
  EXPECT_EQ(keys.error().message.rfind("/1: key time 0 is not after", 0), 0u) << keys.error().message;

  auto curve = easingCurveFromJson(Json::parse(R"({"type": "bezier", "handles": [1.5, 0, 0.5, 1]})"));
  ASSERT_FALSE(curve.ok());
  EXPECT_EQ(curve.error().kind, eng::ErrorKind::Malformed);
  EXPECT_EQ(curve.error().message.rfind("/handles: bezier handle x must lie in [0,1]", 0), 0u) << curve.error().message;
  EXPECT_FALSE(easingCurveFromJson(Json("bouncy")).ok());
  auto cosine = easingCurveFromJson(Json("cosine"));
  ASSERT_TRUE(cosine.ok());
  EXPECT_EQ(cosine->type(), EasingType::Cosine);
}

// A key is a weight: one outside what any rig uses is refused at its pointer;
// 1e38 (which overflows once scaled or summed) already by the range of every
// number in the file (NumberRange.*).
TEST(TimelineJsonValidity, KeyValuesOutsideTheWeightRangeAreRefused) {
  std::string e = loadError("huge", R"({"version": 1, "tracks": [
      {"channel": "a", "keys": [[0, 0], [1, 1e38]]}]})");
  EXPECT_NE(e.find("huge.json: /tracks/0/keys/1/1: number 1e+38 is outside [-1e+06, 1e+06]"), std::string::npos) << e;
  e = loadError("large", R"({"version": 1, "tracks": [{"channel": "a", "keys": [[0, 0], [1, 11]]}]})");
  EXPECT_NE(e.find("large.json: /tracks/0/keys/1: weight 11 is outside [-10, 10]"), std::string::npos) << e;
  e = loadError("negative", R"({"version": 1, "tracks": [{"channel": "a", "keys": [{"t": 0, "v": -10.5}]}]})");
  EXPECT_NE(e.find("negative.json: /tracks/0/keys/0: weight -10.5 is outside [-10, 10]"), std::string::npos) << e;
  auto edge = timelineFromJson(Json::parse(R"({"tracks": [{"channel": "a", "keys": [[0, -10], [1, 10]]}]})"), "edge");
  EXPECT_TRUE(edge.ok()) << edge.error().message;
}

TEST(TimelineJson, TangentModesAreReadResolvedAndWrittenBack) {
  // An auto key's slopes come from its neighbours whatever "in"/"out" say; a
  // key without "tangent" (every older file) keeps its slopes as written.
  auto t = loadTimeline(writeTimeline("tangents", R"({"version": 1, "tracks": [{"channel": "a", "keys": [
      [0, 0],
      {"t": 1, "v": 0.5, "interp": "hermite", "tangent": "auto", "in": 9, "out": 9},
      {"t": 2, "v": 1, "interp": "hermite", "in": 0.25, "out": -3},
      {"t": 3, "v": 1, "tangent": "flat"}]}]})"));
  ASSERT_TRUE(t.ok()) << t.error().message;
  const auto keys = t->trackKeys(0);
  EXPECT_EQ(keys[1].tangent, TangentMode::Auto);
  EXPECT_FLOAT_EQ(keys[1].outTangent, 0.5f);
  EXPECT_FLOAT_EQ(keys[2].inTangent, 0.25f);
  EXPECT_FLOAT_EQ(keys[2].outTangent, -3.0f);
  EXPECT_EQ(keys[2].tangent, TangentMode::Broken);
  EXPECT_EQ(keys[3].tangent, TangentMode::Flat);
  const Json written = timelineToJson(*t);
  EXPECT_EQ(written["tracks"][0]["keys"][1]["tangent"], "auto");
  EXPECT_FALSE(written["tracks"][0]["keys"][2].contains("tangent"));
  auto back = timelineFromJson(written, "back");
  ASSERT_TRUE(back.ok()) << back.error().message;
  for (size_t i = 0; i < keys.size(); ++i) {
    EXPECT_EQ(back->keys[i].inTangent, keys[i].inTangent) << i;
    EXPECT_EQ(back->keys[i].outTangent, keys[i].outTangent) << i;
    EXPECT_EQ(back->keys[i].tangent, keys[i].tangent) << i;
  }
  EXPECT_NE(loadError("bad_tangent", R"({"version": 1, "tracks": [{"channel": "a", "keys": [
      {"t": 0, "v": 0, "tangent": "clamped"}, [1, 1]]}]})").find("unknown tangent mode 'clamped'"), std::string::npos);
}
