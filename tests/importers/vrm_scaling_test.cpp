// VRM 0.x material values name their material: each name is one hashed
// look-up, so n materials and n values read in linear work (issue 37: a
// 5-13 MB file searched every material per value). Work is counted
// (tests/common/work_scaling.h).
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "importers/vrm_import.h"
#include "tests/common/work_scaling.h"

namespace {

using Json = nlohmann::ordered_json;

// n materials and one expression with a colour value for each, last first.
Json vrm0WithMaterials(size_t n) {
  Json doc = Json::parse(R"({
    "asset": {"version": "2.0"},
    "nodes": [{"mesh": 0}],
    "meshes": [{"name": "Body", "primitives": [{"attributes": {}, "targets": [{}]}]}],
    "extensions": {"VRM": {"blendShapeMaster": {"blendShapeGroups": [
      {"name": "Joy", "presetName": "joy", "binds": [{"mesh": 0, "index": 0, "weight": 100}]}]}}}
  })");
  doc["materials"] = Json::array();
  Json& values = doc["extensions"]["VRM"]["blendShapeMaster"]["blendShapeGroups"][0]["materialValues"];
  values = Json::array();
  for (size_t m = 0; m < n; ++m) {
    doc["materials"].push_back({{"name", "material" + std::to_string(m)}});
    values.push_back({{"materialName", "material" + std::to_string(n - 1 - m)}, {"propertyName", "_Color"},
                      {"targetValue", {1, 0, 0, 1}}});
  }
  return doc;
}

TEST(VrmScaling, MaterialValuesFindTheirMaterialsInLinearWork) {
  testing_support::expectLinearWork([](size_t n) {
    auto set = importers::importVrmExpressions(vrm0WithMaterials(n), "avatar.vrm");
    ASSERT_TRUE(set) << set.error().message;
    ASSERT_EQ(set->materialColorBinds.size(), n);
    EXPECT_EQ(set->materialColorBinds.front().material, n - 1);
    EXPECT_TRUE(set->warnings.empty()) << set->warnings.front();
  }, 500);
}

}  // namespace
