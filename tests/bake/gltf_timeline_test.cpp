#include "bake/gltf_timeline.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "tests/common/test_support.h"
#include "tests/facial/graph/graph_test_support.h"

using namespace facial;

namespace {

// One node, one mesh with targets a, b, c (defaults 0, 0.25, 0), no geometry needed.
eng::Model threeTargetModel() {
  eng::Model model;
  model.meshes.push_back({.name = "face", .targetNames = {"a", "b", "c"}, .defaultWeights = {0.0f, 0.25f, 0.0f}});
  model.nodes.push_back({.name = "head", .mesh = 0});
  model.roots = {0};
  return model;
}

// glTF sampler semantics, written out from the specification as the oracle.
float gltfSample(const eng::WeightsChannel& ch, size_t target, float time) {
  const auto& t = ch.times;
  const size_t n = ch.targetCount;
  const bool cubic = ch.interpolation == eng::Interpolation::CubicSpline;
  auto value = [&](size_t k) { return ch.values[k * n * (cubic ? 3 : 1) + (cubic ? n : 0) + target]; };
  if (time <= t.front()) return value(0);
  if (time >= t.back()) return value(t.size() - 1);
  size_t k = 0;
  while (t[k + 1] <= time) ++k;
  const float td = t[k + 1] - t[k], s = (time - t[k]) / td;
  switch (ch.interpolation) {
    case eng::Interpolation::Step: return value(k);
    case eng::Interpolation::Linear: return value(k) + s * (value(k + 1) - value(k));
    case eng::Interpolation::CubicSpline: {
      const float b = ch.values[k * 3 * n + 2 * n + target], a = ch.values[(k + 1) * 3 * n + target];
      const float s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * value(k) + td * (s3 - 2 * s2 + s) * b + (-2 * s3 + 3 * s2) * value(k + 1) +
             td * (s3 - s2) * a;
    }
  }
  return 0.0f;
}

void expectSameCurves(const Timeline& expected, const Timeline& actual, float tolerance, float skipBeforeSteps = 0.0f) {
  for (size_t i = 0; i < expected.tracks.size(); ++i) {
    const TimelineTrack* back = actual.findTrack(expected.tracks[i].channel);
    ASSERT_NE(back, nullptr) << expected.tracks[i].channel;
    const auto keysA = expected.trackKeys(i);
    const auto keysB = actual.trackKeys(static_cast<size_t>(back - actual.tracks.data()));
    for (float time = -0.1f; time <= expected.duration + 0.1f; time += 1.0f / 997) {
      bool nearStep = false;
      for (size_t k = 0; k + 1 < keysA.size(); ++k)
        nearStep = nearStep || (keysA[k].interpolation == KeyInterpolation::Step && time > keysA[k + 1].time - skipBeforeSteps &&
                                time < keysA[k + 1].time);
      if (nearStep) continue;
      EXPECT_NEAR(sampleKeys(keysB, time), sampleKeys(keysA, time), tolerance)
          << expected.tracks[i].channel << " at " << time;
    }
  }
}

Timeline roundTrip(const Timeline& timeline, eng::Interpolation expected) {
  eng::Model model = threeTargetModel();
  auto exported = bake::exportGltfTimeline(model, timeline);
  EXPECT_TRUE(exported.ok()) << exported.error().message;
  EXPECT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(model.animations[0].channels[0].interpolation, expected);
  auto back = bake::importGltfTimeline(model, 0);
  EXPECT_TRUE(back.ok()) << back.error().message;
  return back.ok() ? back.value() : Timeline{};
}

}  // namespace

TEST(GltfTimeline, ImportsCubicSplineKeysAsHermiteWithTheGltfTangents) {
  eng::Model model = threeTargetModel();
  // Two keys x (in-tangents a b c, values a b c, out-tangents a b c).
  model.animations.push_back({"smile", {eng::WeightsChannel{.node = 0, .mesh = 0, .interpolation = eng::Interpolation::CubicSpline,
                                                            .targetCount = 3, .times = {0.5f, 1.5f},
                                                            .values = {0, 0, 0, 0.1f, 0.2f, 0.3f, 1, 2, 3,
                                                                       -1, -2, -3, 0.9f, 0.8f, 0.7f, 0, 0, 0}}}});
  auto timeline = bake::importGltfTimeline(model, 0);
  ASSERT_TRUE(timeline.ok()) << timeline.error().message;
  EXPECT_EQ(timeline->name, "smile");
  EXPECT_FLOAT_EQ(timeline->duration, 1.5f);
  ASSERT_EQ(timeline->tracks.size(), 3u);
  EXPECT_EQ(timeline->tracks[1].channel, "b");
  const auto b = timeline->trackKeys(1);
  EXPECT_EQ(b[0].interpolation, KeyInterpolation::Hermite);
  EXPECT_FLOAT_EQ(b[0].value, 0.2f);
  EXPECT_FLOAT_EQ(b[0].outTangent, 2.0f);
  EXPECT_FLOAT_EQ(b[1].inTangent, -2.0f);
  EXPECT_FLOAT_EQ(b[1].value, 0.8f);
  for (float time = 0.0f; time < 2.0f; time += 0.01f)
    for (size_t t = 0; t < 3; ++t)
      EXPECT_NEAR(sampleKeys(timeline->trackKeys(t), time), gltfSample(model.animations[0].channels[0], t, time), 1e-5f);
}

TEST(GltfTimeline, LinearAndHermiteMixExportsAsExactCubicSpline) {
  Timeline t;
  t.name = "mix";
  t.duration = 2.0f;
  t.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f, 0, 3.0f, KeyInterpolation::Hermite}, {0.7f, 0.9f, -1.0f, 0.5f, KeyInterpolation::Linear},
                                        {1.3f, 0.2f, 0, 0, KeyInterpolation::Hermite}, {2.0f, 0.6f, 2.0f, 0}});
  t.addTrack("c", std::vector<Keyframe>{{0.25f, 1.0f}, {1.0f, 0.0f}});
  const Timeline back = roundTrip(t, eng::Interpolation::CubicSpline);
  expectSameCurves(t, back, 2e-6f);
}

TEST(GltfTimeline, StepOnlyAndLinearOnlyExportWithTheirOwnInterpolation) {
  Timeline steps;
  steps.name = "steps";
  steps.duration = 1.0f;
  steps.addTrack("b", std::vector<Keyframe>{{0.0f, 0.1f, 0, 0, KeyInterpolation::Step}, {0.4f, 0.8f, 0, 0, KeyInterpolation::Step}, {1.0f, 0.3f}});
  expectSameCurves(steps, roundTrip(steps, eng::Interpolation::Step), 0.0f);

  Timeline lines;
  lines.name = "lines";
  lines.duration = 1.0f;
  lines.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f}, {0.3f, 1.0f}, {1.0f, 0.5f}});
  lines.addTrack("b", std::vector<Keyframe>{{0.5f, 0.5f}, {0.9f, 0.0f}});
  expectSameCurves(lines, roundTrip(lines, eng::Interpolation::Linear), 1e-6f);
}

TEST(GltfTimeline, CosineAndStepInsideCubicExportAreCloseApproximations) {
  Timeline t;
  t.name = "talk";
  t.duration = 2.0f;
  t.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f, 0, 0, KeyInterpolation::Cosine}, {1.0f, 1.0f, 0, 0, KeyInterpolation::Step},
                                        {1.5f, 0.2f, 0, 0, KeyInterpolation::Hermite}, {2.0f, 0.4f}});
  const Timeline back = roundTrip(t, eng::Interpolation::CubicSpline);
  expectSameCurves(t, back, 1e-5f, /*skipBeforeSteps=*/bake::GltfTimelineExport{}.stepRamp);
}

// One cosine segment of 18 hours is 1.9 million keys at 30 a second: with
// every target of an ARKit face at each, 1.2 GB from a few bytes of timeline.
// The keys are counted and charged before any is made (issue 37).
TEST(GltfTimelineBudget, KeysOfALongCosineSegmentAreChargedFirst) {
  eng::Model model;
  eng::Mesh face{.name = "face"};
  for (int t = 0; t < 52; ++t) face.targetNames.push_back("t" + std::to_string(t));
  face.defaultWeights.assign(52, 0.0f);
  model.meshes.push_back(std::move(face));
  model.nodes.push_back({.name = "head", .mesh = 0});
  Timeline t;
  t.name = "long";
  t.duration = 18 * 3600.0f;
  t.addTrack("t0", std::vector<Keyframe>{{0.0f, 0.0f, 0, 0, KeyInterpolation::Cosine}, {t.duration, 1.0f}});
  auto exported = bake::exportGltfTimeline(model, t);
  ASSERT_FALSE(exported);
  EXPECT_EQ(exported.error().kind, eng::ErrorKind::TooLarge);
  EXPECT_NE(exported.error().message.find("timeline 'long': 1944004 glTF keys of 52 targets would take"), std::string::npos)
      << exported.error().message;
  EXPECT_NE(exported.error().message.find("load budget of " + std::to_string(eng::kDefaultLoadBudgetBytes)), std::string::npos)
      << exported.error().message;
  EXPECT_TRUE(model.animations.empty());
  // The embedder's budget: an hour (68 MB of keys) fits 128 MB, the 18 hours do not.
  bake::GltfTimelineExport options;
  options.maxBytes = size_t{128} << 20;
  EXPECT_FALSE(bake::exportGltfTimeline(model, t, options));
  Timeline hour;
  hour.name = "hour";
  hour.duration = 3600.0f;
  hour.addTrack("t0", std::vector<Keyframe>{{0.0f, 0.0f, 0, 0, KeyInterpolation::Cosine}, {hour.duration, 1.0f}});
  auto fits = bake::exportGltfTimeline(model, hour, options);
  ASSERT_TRUE(fits) << fits.error().message;
  EXPECT_EQ(model.animations.back().channels[0].times.size(), size_t{108'001});
}

TEST(GltfTimeline, TargetsWithoutATrackHoldTheMeshDefault) {
  Timeline t;
  t.name = "only a";
  t.duration = 1.0f;
  t.addTrack("a", std::vector<Keyframe>{{0.0f, 0.0f}, {1.0f, 1.0f}});
  eng::Model model = threeTargetModel();
  ASSERT_TRUE(bake::exportGltfTimeline(model, t).ok());
  const eng::WeightsChannel& ch = model.animations[0].channels[0];
  EXPECT_EQ(ch.node, 0);
  EXPECT_EQ(ch.targetCount, 3u);
  EXPECT_FLOAT_EQ(gltfSample(ch, 1, 0.5f), 0.25f);
  EXPECT_FLOAT_EQ(gltfSample(ch, 0, 0.5f), 0.5f);
}

TEST(GltfTimelineValidity, BadChannelsAndTargetsAreNamed) {
  eng::Model model = threeTargetModel();
  model.animations.push_back({"short", {eng::WeightsChannel{.node = 0, .mesh = 0, .targetCount = 3, .times = {0, 1}, .values = {0, 0, 0}}}});
  auto e = bake::importGltfTimeline(model, 0);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("animation 0 'short' channel 0: 3 values for 2 keys of 3"), std::string::npos) << e.error().message;

  model.animations[0].channels[0] = {.node = 0, .mesh = 0, .targetCount = 3, .times = {1, 1}, .values = {0, 0, 0, 0, 0, 0}};
  e = bake::importGltfTimeline(model, 0);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("strictly increasing"), std::string::npos) << e.error().message;

  model.animations[0].channels[0] = {.node = 0, .mesh = 0, .targetCount = 2, .times = {0, 1}, .values = {0, 0, 0, 0}};
  EXPECT_NE(bake::importGltfTimeline(model, 0).error().message.find("2 weights per key, mesh 'face' has 3 targets"), std::string::npos);
  EXPECT_FALSE(bake::importGltfTimeline(model, 5).ok());

  Timeline t;
  t.name = "x";
  t.duration = 1.0f;
  t.addTrack("jawOpen", std::vector<Keyframe>{{0.0f, 0.0f}});
  eng::Model target = threeTargetModel();
  auto missing = bake::exportGltfTimeline(target, t);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("'jawOpen', which is not a morph target of mesh 'face'"), std::string::npos);
  target.nodes[0].mesh = -1;
  EXPECT_NE(bake::exportGltfTimeline(target, t).error().message.find("has no mesh"), std::string::npos);
  EXPECT_TRUE(target.animations.empty());
}

TEST(GltfTimelineSharedAssets, ImportsEveryWeightsAnimationAsTheGltfSamplerPlaysIt) {
  FACIAL_REQUIRE_SHARED();
  const auto assets = testing_support::sharedDir() / "assets";
  for (const char* file : {"facecap.glb", "RobotExpressive.glb", "khronos/MorphStressTest/MorphStressTest.gltf",
                           "khronos/AnimatedMorphCube/AnimatedMorphCube.gltf"}) {
    auto model = eng::loadModel(assets / file);
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto imported = bake::importGltfTimelines(*model);
    ASSERT_TRUE(imported.ok()) << file << ": " << imported.error().message;
    ASSERT_FALSE(imported->timelines.empty()) << file;
    std::mt19937 rng(3);
    size_t timelineIndex = 0;
    for (const eng::Animation& animation : model->animations) {
      if (animation.channels.empty()) continue;
      const Timeline& timeline = imported->timelines[timelineIndex++];
      EXPECT_EQ(timeline.name, animation.name);
      const eng::WeightsChannel& ch = animation.channels[0];
      const eng::Mesh& mesh = model->meshes[ch.mesh];
      std::uniform_real_distribution<float> when(0.0f, timeline.duration);
      for (int probe = 0; probe < 50; ++probe) {
        const float time = when(rng);
        for (size_t t = 0; t < ch.targetCount; ++t) {
          const TimelineTrack* track = timeline.findTrack(mesh.targetNames[t]);
          ASSERT_NE(track, nullptr);
          EXPECT_NEAR(sampleKeys(timeline.trackKeys(static_cast<size_t>(track - timeline.tracks.data())), time),
                      gltfSample(ch, t, time), 1e-5f)
              << file << " " << animation.name << " " << mesh.targetNames[t] << " at " << time;
        }
      }
    }
  }
}

TEST(GltfTimelineSharedAssets, FacecapAnimationPlaysInAGraphAndSurvivesAGlbRoundTrip) {
  FACIAL_REQUIRE_SHARED();
  auto model = eng::loadModel(testing_support::sharedDir() / "assets" / "facecap.glb");
  ASSERT_TRUE(model.ok()) << model.error().message;
  auto imported = bake::importGltfTimelines(*model);
  ASSERT_TRUE(imported.ok()) << imported.error().message;
  ASSERT_EQ(imported->timelines.size(), 1u);
  const Timeline& take = imported->timelines[0];
  const eng::WeightsChannel& source = model->animations[0].channels[0];
  const eng::Mesh& face = model->meshes[source.mesh];
  ASSERT_EQ(take.tracks.size(), 52u);

  // Played through a graph over the mesh's own target names.
  auto channels = ChannelSet::fromNames(face.targetNames);
  ASSERT_TRUE(channels.ok());
  GraphBuilder builder(*channels);
  builder.setRoot(builder.add(TimelineNode{.timeline = builder.addTimeline(take)}));
  GraphInstance player = graph_test::instantiate(graph_test::buildGraph(builder));
  float time = 0.0f;
  for (int frame = 0; frame < 300; ++frame) {
    player.update(1.0f / 30.0f);
    time += 1.0f / 30.0f;
    const size_t jaw = *channels->find("jawOpen");
    ASSERT_NEAR(player.weights()[jaw], std::clamp(gltfSample(source, jaw, time), 0.0f, 1.0f), 1e-4f) << "frame " << frame;
  }

  // Exported onto the model, written as GLB, loaded and imported again.
  eng::Model copy = *model;
  copy.animations.clear();
  bake::GltfTimelineExport where;
  where.node = source.node;
  ASSERT_TRUE(bake::exportGltfTimeline(copy, take, where).ok());
  const auto path = testing_support::freshTempDir("gltf_timeline_facecap") / "facecap_take.glb";
  auto saved = eng::saveModel(copy, path);
  ASSERT_TRUE(saved.ok()) << saved.error().message;
  auto reloaded = eng::loadModel(path);
  ASSERT_TRUE(reloaded.ok()) << reloaded.error().message;
  auto again = bake::importGltfTimeline(*reloaded, 0);
  ASSERT_TRUE(again.ok()) << again.error().message;
  expectSameCurves(take, *again, 1e-6f);
}
