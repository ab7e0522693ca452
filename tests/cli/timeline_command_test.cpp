// `facial timeline import|export`: JSON timelines to glTF weights animations
// on a model and back, the curve kept; refused input named.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_face.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

namespace fs = std::filesystem;

// Jaw opens linearly and closes with a cosine ease; the custom shape steps.
constexpr const char* kTimeline = R"({"version": 1, "name": "chew", "duration": 2, "tracks": [
  {"channel": "AU26_JawDrop", "keys": [[0, 0], [0.5, 1], {"t": 1.5, "v": 0, "interp": "cosine"}]},
  {"channel": "custom_shape", "keys": [{"t": 0, "v": 0.2, "interp": "step"}, [1, 0.8]]}]})";

float sampleTrack(const facial::Timeline& timeline, const std::string& channel, float time) {
  for (size_t i = 0; i < timeline.tracks.size(); ++i)
    if (timeline.tracks[i].channel == channel) return facial::sampleKeys(timeline.trackKeys(i), time);
  ADD_FAILURE() << "no track " << channel << " in timeline '" << timeline.name << "'";
  return -1.0f;
}

TEST(TimelineCommand, ExportThenImportKeepsTheCurves) {
  const fs::path dir = testing_support::freshTempDir("timeline_round_trip");
  const fs::path face = writeTestFace("timeline_face");
  testing_support::writeFile(dir / "chew.json", kTimeline);

  const CommandOutput exported =
      runFacial({"timeline", "export", (dir / "chew.json").string(), "--model", face.string(), "--out",
                 (dir / "animated.glb").string()});
  ASSERT_EQ(exported.exitCode, 0) << exported.err;
  EXPECT_NE(exported.out.find("animation 'chew' (2 track(s)"), std::string::npos) << exported.out;

  const CommandOutput info = runFacial({"info", (dir / "animated.glb").string()});
  EXPECT_NE(info.out.find("'chew'"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("CUBICSPLINE"), std::string::npos) << "mixed step/linear/cosine needs cubic keys:\n"
                                                             << info.out;

  const CommandOutput imported = runFacial(
      {"timeline", "import", (dir / "animated.glb").string(), "--animation", "chew", "--out",
       (dir / "back.json").string()});
  ASSERT_EQ(imported.exitCode, 0) << imported.err;
  auto original = facial::loadTimeline(dir / "chew.json");
  auto back = facial::loadTimeline(dir / "back.json");
  ASSERT_TRUE(original.ok()) << original.error().message;
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_NEAR(back->duration, 2.0f, 1e-4f);
  // A glTF animation holds the mesh's own weights: marked so that `facial
  // play` drives the targets with them even where they are named like action
  // units (this face's AU26_JawDrop), not through the rig a second time.
  EXPECT_EQ(back->channels, facial::TimelineChannels::Targets);
  // Every target of the mesh gets a track on import (5 on the test face).
  EXPECT_EQ(back->tracks.size(), 5u);
  for (float t = 0.0f; t <= 2.0f; t += 0.05f) {
    EXPECT_NEAR(sampleTrack(*back, "AU26_JawDrop", t), sampleTrack(*original, "AU26_JawDrop", t), 2e-3f) << t;
    // The step holds 0.2 until 1 s, then ramps within a millisecond.
    if (std::abs(t - 1.0f) > 0.01f) {
      EXPECT_NEAR(sampleTrack(*back, "custom_shape", t), sampleTrack(*original, "custom_shape", t), 2e-3f) << t;
    }
  }
}

TEST(TimelineCommand, FacecapAnimationImportsAndExportsOntoTheFaceMesh) {
  FACIAL_REQUIRE_SHARED();
  const fs::path dir = testing_support::freshTempDir("timeline_facecap");
  const CommandOutput imported =
      runFacial({"timeline", "import", facecapPath().string(), "--out", (dir / "take.json").string()});
  ASSERT_EQ(imported.exitCode, 0) << imported.err;
  EXPECT_NE(imported.out.find("52 track(s)"), std::string::npos) << imported.out;
  // facecap's first mesh is not the face: export must find the mesh with the 52 targets.
  const CommandOutput exported = runFacial({"timeline", "export", (dir / "take.json").string(), "--model",
                                            facecapPath().string(), "--out", (dir / "facecap.glb").string()});
  ASSERT_EQ(exported.exitCode, 0) << exported.err;
  auto take = facial::loadTimeline(dir / "take.json");
  ASSERT_TRUE(take.ok()) << take.error().message;
  EXPECT_GT(take->duration, 10.0f);
}

TEST(TimelineCommand, AnFbxTakeImportsAsATimeline) {
  // Blender's baked FBX clip (tests/importers/fbx/animated_face.fbx): the jaw
  // keyed 0 at frame 1, 1 at frame 9, 0.3 at 17 and 0 at 25 (24 frames a second).
  const fs::path take = testing_support::sourceDir() / "tests" / "importers" / "fbx" / "animated_face.fbx";
  const fs::path dir = testing_support::freshTempDir("timeline_fbx");
  const CommandOutput imported = runFacial({"timeline", "import", take.string(), "--out", (dir / "take.json").string()});
  ASSERT_EQ(imported.exitCode, 0) << imported.err;
  EXPECT_NE(imported.out.find("animation 'Scene'"), std::string::npos) << imported.out;
  EXPECT_NE(imported.out.find("2 track(s)"), std::string::npos) << imported.out;
  auto timeline = facial::loadTimeline(dir / "take.json");
  ASSERT_TRUE(timeline.ok()) << timeline.error().message;
  EXPECT_NEAR(sampleTrack(*timeline, "jawOpen", 9.0f / 24.0f), 1.0f, 1e-3f);
  EXPECT_NEAR(sampleTrack(*timeline, "mouthSmile_L", 17.0f / 24.0f), 1.0f, 1e-3f);
}

TEST(TimelineCommandValidity, UnknownAnimationListsTheModelsAnimations) {
  FACIAL_REQUIRE_SHARED();
  const fs::path stress = testing_support::sharedDir() / "assets" / "khronos" / "MorphStressTest" / "MorphStressTest.gltf";
  const CommandOutput run = runFacial({"timeline", "import", stress.string(), "--animation", "nope", "--out",
                                       (testing_support::freshTempDir("timeline_unknown") / "x.json").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("no weights animation 'nope' (it has: 0 'Individuals', 1 'TheWave', 2 'Pulse')"),
            std::string::npos)
      << run.err;
}

TEST(TimelineCommandValidity, ModelWithoutAnimationsIsNamed) {
  const fs::path face = writeTestFace("timeline_no_animation");
  const fs::path out = testing_support::freshTempDir("timeline_no_animation_out") / "x.json";
  const CommandOutput run = runFacial({"timeline", "import", face.string(), "--out", out.string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find(face.string() + ": has no animation of morph target weights"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(TimelineCommandValidity, TrackForAMissingTargetIsNamedAndNothingIsWritten) {
  const fs::path dir = testing_support::freshTempDir("timeline_bad_track");
  const fs::path face = writeTestFace("timeline_bad_track_face");
  testing_support::writeFile(dir / "bad.json",
                             R"({"version": 1, "name": "bad", "duration": 1, "tracks": [
                                  {"channel": "noSuchShape", "keys": [[0, 0], [1, 1]]}]})");
  const CommandOutput run = runFacial({"timeline", "export", (dir / "bad.json").string(), "--model", face.string(),
                                       "--out", (dir / "out.glb").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("'noSuchShape', which is not a morph target"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
}

TEST(TimelineCommandValidity, MalformedTimelineIsNamed) {
  const fs::path dir = testing_support::freshTempDir("timeline_malformed");
  const fs::path face = writeTestFace("timeline_malformed_face");
  testing_support::writeFile(dir / "broken.json", R"({"version": 1, "tracks": [)");
  const CommandOutput run = runFacial({"timeline", "export", (dir / "broken.json").string(), "--model", face.string(),
                                       "--out", (dir / "out.glb").string()});
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find((dir / "broken.json").string()), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
}

}  // namespace
}  // namespace cli_test
