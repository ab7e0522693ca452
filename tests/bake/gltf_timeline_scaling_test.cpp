// Importing glTF weights animations as timelines, and exporting a timeline
// back, does work linear in the targets, channels and keys (issue 37): a
// scan of the tracks per target, or of the targets per track, made a face
// with many targets quadratic. Work is what the code counts (keys read, names
// compared: eng::countWork) plus its heap allocations, at n and 4n.
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake/gltf_timeline.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/work_scaling.h"

namespace {

using testing_support::expectLinearWork;

std::string targetName(size_t i) { return "target_" + std::to_string(i); }

// A channel over all `targets` of `mesh`, LINEAR keys at 0, 1, 2, ... (value k % 2).
eng::WeightsChannel channelOver(int mesh, size_t targets, size_t keys, eng::Interpolation interpolation) {
  eng::WeightsChannel channel{.node = mesh, .mesh = mesh, .interpolation = interpolation, .targetCount = targets};
  const size_t perKey = interpolation == eng::Interpolation::CubicSpline ? 3 : 1;
  for (size_t k = 0; k < keys; ++k) {
    channel.times.push_back(float(k));
    for (size_t v = 0; v < perKey * targets; ++v) channel.values.push_back(float(k % 2) * 0.5f);
  }
  return channel;
}

void expectImportsLinearly(const std::function<eng::Model(size_t)>& model, size_t n, size_t extraTracks) {
  expectLinearWork([&](size_t size) {
    const eng::Model m = model(size);
    eng::resetWorkCount();  // the import, not the making of the model
    testing_support::countAllocationsAsWork([&] {
      std::vector<std::string> warnings;
      auto timeline = bake::importGltfTimeline(m, 0, &warnings);
      ASSERT_TRUE(timeline) << timeline.error().message;
      EXPECT_EQ(timeline->tracks.size(), size + extraTracks);
    });
  }, n);
}

TEST(GltfTimelineScaling, ManyTargetsImportLinearly) {
  expectImportsLinearly([](size_t n) {
    eng::Model model;
    model.meshes.push_back({.name = "face"});
    for (size_t t = 0; t < n; ++t) model.meshes[0].targetNames.push_back(targetName(t));
    model.nodes.push_back({.name = "head", .mesh = 0});
    model.animations.push_back({.name = "clip", .channels = {channelOver(0, n, 3, eng::Interpolation::Linear)}});
    return model;
  }, 500, 0);
}

// n meshes, each with its own target and one they all share: n channels, the
// shared target kept from the first (n - 1 warnings): n + 1 tracks.
TEST(GltfTimelineScaling, ManyChannelsImportLinearly) {
  expectImportsLinearly([](size_t n) {
    eng::Model model;
    model.animations.push_back({.name = "clip"});
    for (size_t m = 0; m < n; ++m) {
      model.meshes.push_back({.name = "part", .targetNames = {targetName(m), "shared"}});
      model.nodes.push_back({.mesh = int(m)});
      model.animations[0].channels.push_back(channelOver(int(m), 2, 3, eng::Interpolation::Step));
    }
    return model;
  }, 300, 1);
}

TEST(GltfTimelineScaling, ManyKeysImportLinearly) {
  expectLinearWork([](size_t n) {
    eng::Model model;
    model.meshes.push_back({.name = "face", .targetNames = {"a", "b", "c", "d"}});
    model.nodes.push_back({.mesh = 0});
    model.animations.push_back({.name = "clip", .channels = {channelOver(0, 4, n, eng::Interpolation::CubicSpline)}});
    eng::resetWorkCount();
    testing_support::countAllocationsAsWork([&] {
      auto timeline = bake::importGltfTimeline(model, 0);
      ASSERT_TRUE(timeline) << timeline.error().message;
      EXPECT_EQ(timeline->keys.size(), 4 * n);
      EXPECT_EQ(timeline->keys[1].interpolation, facial::KeyInterpolation::Hermite);
    });
  }, 2000);
}

// Export finds the node and matches every track to a target through a hash:
// n nodes draw a mesh lacking one track's target, the last node one that has
// all n. Keys share their times, so the output is 2 keys x n targets.
TEST(GltfTimelineScaling, ExportMatchesTracksAndNodesLinearly) {
  expectLinearWork([](size_t n) {
    eng::Model model;
    model.meshes.push_back({.name = "partial"});
    model.meshes.push_back({.name = "face"});
    for (size_t t = 0; t < n; ++t) {
      if (t + 1 < n) model.meshes[0].targetNames.push_back(targetName(t));
      model.meshes[1].targetNames.push_back(targetName(t));
    }
    for (size_t i = 0; i < n; ++i) model.nodes.push_back({.mesh = 0});
    model.nodes.push_back({.name = "head", .mesh = 1});
    facial::Timeline timeline;
    timeline.name = "clip";
    for (size_t t = 0; t < n; ++t) {
      const facial::Keyframe keys[] = {{.time = 0, .value = 0}, {.time = 1, .value = 1}};
      timeline.addTrack(targetName(t), keys);
    }
    timeline.duration = 1;
    eng::resetWorkCount();
    testing_support::countAllocationsAsWork([&] {
      auto exported = bake::exportGltfTimeline(model, timeline);
      ASSERT_TRUE(exported) << exported.error().message;
    });
    ASSERT_EQ(model.animations.size(), 1u);
    EXPECT_EQ(model.animations[0].channels[0].node, int(n));
    EXPECT_EQ(model.animations[0].channels[0].values.size(), 2 * n);
  }, 300);
}

}  // namespace
