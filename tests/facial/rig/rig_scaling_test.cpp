// Rig files resolve names by hash (issue 37): a rig map's n entries on a
// model of n targets, or n look-ups among n expression presets, are linear
// work, not a scan per name. Work is counted (tests/common/work_scaling.h).
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "tests/common/work_scaling.h"

namespace {

TEST(RigMapScaling, EntriesFindTheirTargetsInLinearWork) {
  testing_support::expectLinearWork([](size_t n) {
    std::vector<std::string> targets;
    nlohmann::json list = nlohmann::json::array();
    for (size_t t = 0; t < n; ++t) {
      targets.push_back("target" + std::to_string(t));
      list.push_back({{"target", "target" + std::to_string(n - 1 - t)}, {"weight", 0.5}});
    }
    const nlohmann::json file = {{"version", 1}, {"map", {{"AU1_InnerBrowRaiser", list}}}};
    auto mapping = facial::parseRigMap(file.dump(), "map.json", targets);
    ASSERT_TRUE(mapping) << mapping.error().message;
  }, 500);
}

TEST(RigMapScaling, EveryTargetOfARepeatedNameIsDriven) {
  const std::vector<std::string> targets{"blink", "smile", "blink", "blink"};
  auto mapping = facial::parseRigMap(R"({"version": 1, "map": {"AU1_InnerBrowRaiser": [{"target": "blink", "weight": 1}]}})",
                                     "map.json", targets);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(std::vector<uint32_t>(mapping->drivenTargets().begin(), mapping->drivenTargets().end()),
            (std::vector<uint32_t>{0, 2, 3}));
}

TEST(ExpressionLibraryScaling, PresetsAreFoundInLinearWork) {
  testing_support::expectLinearWork([](size_t n) {
    nlohmann::json expressions = nlohmann::json::object();
    for (size_t i = 0; i < n; ++i)
      expressions["preset" + std::to_string(i)] = {{"actionUnits", {{"AU1_InnerBrowRaiser", 0.5}}}};
    auto library = facial::ExpressionLibrary::parse(nlohmann::json{{"version", 1}, {"expressions", expressions}}.dump(), "e.json");
    ASSERT_TRUE(library) << library.error().message;
    for (size_t i = 0; i < n; ++i) ASSERT_NE(library->find("preset" + std::to_string(i)), nullptr);
    EXPECT_EQ(library->find("preset"), nullptr);
  }, 500);
}

}  // namespace
