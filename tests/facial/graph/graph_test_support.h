#pragma once
// Helpers shared by the animation graph tests.
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/graph_instance.h"
#include "facial/runtime/graph/preset_lookup.h"

namespace graph_test {

// A small channel set for node tests: three channels, no regions.
inline facial::ChannelSet threeChannels() {
  const std::vector<std::string> names = {"a", "b", "c"};
  return facial::ChannelSet::fromNames(names).value();
}

// Builds or fails the test with the builder's message.
inline facial::SharedGraphDefinition buildGraph(const facial::GraphBuilder& builder) {
  auto graph = builder.build();
  EXPECT_TRUE(graph.ok()) << graph.error().message;
  return graph.ok() ? graph.value() : nullptr;
}

inline facial::GraphInstance instantiate(const facial::SharedGraphDefinition& graph, uint64_t seed = 0) {
  auto instance = facial::GraphInstance::create(graph, seed);
  EXPECT_TRUE(instance.ok());
  return std::move(instance).value();
}

// The build error message (empty when the build unexpectedly succeeds).
inline std::string buildError(const facial::GraphBuilder& builder) {
  auto graph = builder.build();
  EXPECT_FALSE(graph.ok()) << "build succeeded where it should fail";
  return graph.ok() ? std::string() : graph.error().message;
}

inline facial::NodeIndex addPose(facial::GraphBuilder& builder, std::vector<float> weights,
                                 facial::VrmOverride overrideBlink = facial::VrmOverride::None) {
  return builder.add(facial::PoseNode{.weights = std::move(weights), .overrideBlink = overrideBlink});
}

// Preset lookup over a fixed table of action-unit poses (name -> {AU channel: weight}),
// scaled by intensity like the rig layer's library.
inline facial::PresetLookup tablePresets(std::map<std::string, std::map<std::string, float>> table) {
  return [table = std::move(table)](std::string_view name, float intensity,
                                    std::span<float> au) -> eng::Result<void> {
    auto it = table.find(std::string(name));
    if (it == table.end()) return eng::makeError(eng::ErrorKind::NotFound, "unknown preset '" + std::string(name) + "'");
    std::fill(au.begin(), au.end(), 0.0f);
    for (const auto& [channel, weight] : it->second) au[*facial::actionUnitIndex(channel)] = weight * intensity;
    return {};
  };
}

}  // namespace graph_test
