// Export .glb (editor/glb_export.h): a clip keyed on rig channels comes out
// as glTF weights animations that pose the face as the editor posed it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/face_setup.h"
#include "bake/gltf_timeline.h"
#include "editor/glb_export.h"
#include "engine/scene/gltf_loader.h"
#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/graph/timeline_json.h"
#include "facial/runtime/json/json_document.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

struct Head {
  app::FaceSetup face;
  editor::TimelineDocument clip;
};

Head headWithTalk() {
  auto face = app::FaceSetup::load({.model = testing_support::sourceDir() / "data" / "head.glb"});
  EXPECT_TRUE(face) << face.error().message;
  auto clip = editor::TimelineDocument::load(testing_support::sourceDir() / "data" / "timelines" / "talk.json");
  EXPECT_TRUE(clip) << clip.error().message;
  return {std::move(*face), std::move(*clip)};
}

// The weights a model's animation gives every target of `layout` at `time` (defaults where it has no track).
std::vector<float> animatedWeights(const facial::Timeline& timeline, const eng::WeightLayout& layout, std::span<const float> base,
                                   float time) {
  std::vector<float> out(base.begin(), base.end());
  const std::vector<std::string> names = layout.names();
  for (size_t t = 0; t < timeline.tracks.size(); ++t) {
    const auto it = std::find(names.begin(), names.end(), timeline.tracks[t].channel);
    if (it == names.end()) continue;
    out[size_t(it - names.begin())] = facial::sampleKeys(timeline.trackKeys(t), time);
  }
  return out;
}

TEST(GlbExport, ClipOnRigChannelsBecomesTheTargetWeightsTheEditorShows) {
  Head head = headWithTalk();
  editor::TimelinePose pose(head.face.rig(), head.face.baseWeights());
  const eng::WeightLayout& layout = head.face.layout();
  const fs::path out = testing_support::freshTempDir("editor_glb_export") / "talk.glb";
  const editor::TimelineDocument* clips[] = {&head.clip};
  auto summary = editor::exportGlb(head.face.model(), clips, pose, layout, out);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->animations, 1u);

  auto model = eng::loadModel(out);
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_FALSE(model->animations.empty());
  auto timeline = bake::importGltfTimeline(*model, model->animations.size() - 1);
  ASSERT_TRUE(timeline) << timeline.error().message;
  EXPECT_EQ(timeline->name, head.clip.name());
  EXPECT_NEAR(timeline->duration, head.clip.duration(), 1e-4f);
  EXPECT_GT(timeline->tracks.size(), 3u) << "the jaw, the lips and more move in talk.json";

  std::vector<float> shown(layout.total());
  float worst = 0.0f, worstBetween = 0.0f;
  for (int k = 0; k <= int(head.clip.duration() * 60.0f); ++k) {
    const float t = float(k) / 60.0f;
    ASSERT_TRUE(pose.pose(head.clip, t, shown));
    const std::vector<float> played = animatedWeights(*timeline, layout, head.face.baseWeights(), t);
    for (size_t i = 0; i < shown.size(); ++i) (k % 2 == 0 ? worst : worstBetween) = std::max(k % 2 == 0 ? worst : worstBetween, std::abs(played[i] - shown[i]));
  }
  EXPECT_LT(worst, 1e-4f) << "at the 30 Hz samples the glb holds exactly what the editor shows";
  EXPECT_LT(worstBetween, 0.05f) << "between samples, linear keys stay close to the clip's curves";
}

TEST(GlbExport, ClipWhereNothingMovesIsLeftOut) {
  Head head = headWithTalk();
  editor::TimelinePose pose(head.face.rig(), head.face.baseWeights());
  const editor::TimelineDocument still("still", 1.0f);
  auto sampled = editor::sampleClipWeights(still, pose, head.face.layout());
  ASSERT_TRUE(sampled) << sampled.error().message;
  EXPECT_EQ(sampled->mesh, -1);
  EXPECT_TRUE(sampled->timeline.tracks.empty());
  EXPECT_FALSE(editor::sampleClipWeights(head.clip, pose, head.face.layout(), 0.0f));
}

TEST(GlbExport, APlaceThatCannotBeWrittenLeavesNothing) {
  Head head = headWithTalk();
  editor::TimelinePose pose(head.face.rig(), head.face.baseWeights());
  const fs::path dir = testing_support::freshTempDir("editor_glb_export_blocked");
  const editor::TimelineDocument* clips[] = {&head.clip};
  auto failed = editor::exportGlb(head.face.model(), clips, pose, head.face.layout(), dir / "missing" / "out.glb");
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.error().message.find("out.glb"), std::string::npos) << "[" << failed.error().message << "]";
  EXPECT_TRUE(fs::is_empty(dir));
}

// What `facial play` does with an exported clip: `facial timeline import`, a
// one-node graph on the imported tracks, stepped frame by frame (frame 0 with
// dt 0, frame k at k / fps). The graph's channel for each target at frame k is
// the editor's weight at k / fps: no sample off by one, no time shift. (Its
// channels, not the driver's target weights: a head whose targets are all named
// like action units has them mapped through the rig a second time by the
// driver; see docs/editor.md.)
TEST(GlbExport, FacialPlayFrameKShowsTheEditorsPoseAtKOverFps) {
  Head head = headWithTalk();
  auto happy = head.clip.addTrack("happy");
  ASSERT_TRUE(happy) << happy.error().message;
  ASSERT_TRUE(head.clip.setKey(*happy, 0.0f, 0.0f, facial::KeyInterpolation::Cosine));
  ASSERT_TRUE(head.clip.setKey(*happy, 1.0f, 1.0f, facial::KeyInterpolation::Cosine));
  ASSERT_TRUE(head.clip.setKey(*happy, 1.7f, 0.2f, facial::KeyInterpolation::Cosine));
  editor::TimelinePose pose(head.face.rig(), head.face.baseWeights(), &head.face.expressions());
  const fs::path dir = testing_support::freshTempDir("editor_glb_export_play");
  const editor::TimelineDocument* clips[] = {&head.clip};
  auto summary = editor::exportGlb(head.face.model(), clips, pose, head.face.layout(), dir / "out.glb");
  ASSERT_TRUE(summary) << summary.error().message;
  auto played = app::FaceSetup::load({.model = dir / "out.glb"});
  ASSERT_TRUE(played) << played.error().message;
  auto timeline = bake::importGltfTimeline(played->model(), played->model().animations.size() - 1);
  ASSERT_TRUE(timeline) << timeline.error().message;
  ASSERT_TRUE(facial::saveTimeline(*timeline, dir / "played.json"));
  facial::Json channels = facial::Json::array();
  for (const facial::TimelineTrack& track : timeline->tracks) channels.push_back(track.channel);
  const facial::Json document = {{"version", facial::kGraphFileVersion},
                                 {"channels", channels},
                                 {"timelines", {{"clip", (dir / "played.json").string()}}},
                                 {"root", {{"type", "timeline"}, {"timeline", "clip"}}}};
  auto graph = facial::parseGraph(document, dir / "played.json",
                                  {.presets = facial::presetLookup(played->expressions()), .allowOutsidePaths = true});
  ASSERT_TRUE(graph) << graph.error().message;
  const std::vector<std::string> names = played->layout().names();
  auto driver = facial::FaceDriver::create(*graph, &played->graphRig(), names, played->baseWeights());
  ASSERT_TRUE(driver) << driver.error().message;
  ASSERT_EQ(names, head.face.layout().names());

  const float fps = 10.0f;
  std::vector<float> shown(head.face.layout().total());
  float worst = 0.0f;
  int worstFrame = -1;
  for (int k = 0; float(k) / fps <= head.clip.duration(); ++k) {
    ASSERT_TRUE(driver->update(k == 0 ? 0.0f : 1.0f / fps));
    ASSERT_TRUE(pose.pose(head.clip, float(k) / fps, shown));
    for (size_t c = 0; c < timeline->tracks.size(); ++c) {
      const size_t target = size_t(std::find(names.begin(), names.end(), timeline->tracks[c].channel) - names.begin());
      ASSERT_LT(target, names.size()) << timeline->tracks[c].channel;
      const float error = std::abs(driver->channelWeights()[c] - shown[target]);
      if (error > worst) worst = error, worstFrame = k;
    }
  }
  EXPECT_LT(worst, 1e-4f) << "frame " << worstFrame << ": play's frame k holds the 30 Hz sample at k / fps exactly";
}

}  // namespace
