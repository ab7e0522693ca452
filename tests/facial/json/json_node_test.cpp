// JsonNode (facial/runtime/json/json_node.h): reads that name the value's JSON pointer.
#include "facial/runtime/json/json_node.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace facial {
namespace {

TEST(JsonNode, MembersKeepFileOrderAndPointers) {
  const Json doc = Json::parse(R"({"map": {"zeta": 1, "a/b": 2, "mid": 3}})");
  const JsonNode map = *JsonNode(doc, "").at("map");
  auto members = map.members();
  ASSERT_TRUE(members) << members.error().message;
  std::vector<std::string> keys, pointers;
  for (const auto& [key, value] : *members) {
    keys.emplace_back(key);
    pointers.push_back(value.pointer());
  }
  EXPECT_EQ(keys, (std::vector<std::string>{"zeta", "a/b", "mid"}));
  EXPECT_EQ(pointers, (std::vector<std::string>{"/map/zeta", "/map/a~1b", "/map/mid"}));
  EXPECT_EQ(*(*members)[2].second.number(), 3.0f);
}

TEST(JsonNodeValidity, MembersOfANonObjectNameItsType) {
  const Json doc = Json::parse(R"({"map": [1, 2]})");
  auto members = JsonNode(doc, "").at("map")->members();
  ASSERT_FALSE(members);
  EXPECT_EQ(members.error().kind, eng::ErrorKind::Malformed);
  EXPECT_EQ(members.error().message, "/map: expected an object, got array");
}

}  // namespace
}  // namespace facial
