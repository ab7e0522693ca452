// Export .glb (editor/glb_export.h): a clip keyed on rig channels comes out
// as glTF weights animations that pose the face as the editor posed it.
#include <gtest/gtest.h>

#include <cmath>

#include "app/face_setup.h"
#include "bake/gltf_timeline.h"
#include "editor/glb_export.h"
#include "engine/scene/gltf_loader.h"
#include "facial/runtime/graph/timeline_json.h"
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

}  // namespace
