#include "facial/runtime/graph/detail/node_reader.h"

#include <string>
#include <utility>
#include <variant>

#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/node.h"

namespace facial::detail {
namespace {

// "pose, blend, ... or blink": the JSON names of NodeData's alternatives.
template <size_t... I>
std::string typeList(std::index_sequence<I...>) {
  std::string out;
  constexpr size_t n = sizeof...(I);
  ((out += (I == 0 ? "" : I + 1 == n ? " or " : ", ") + std::string(std::variant_alternative_t<I, NodeData>::kType)),
   ...);
  return out;
}

// Reads j as the alternative whose kType is `type`; nullopt when none is.
template <size_t... I>
std::optional<NodeData> readAs(std::string_view type, const JsonNode& j, NodeReader& reader,
                               std::index_sequence<I...>) {
  std::optional<NodeData> out;
  ((std::variant_alternative_t<I, NodeData>::kType == type
        ? (void)out.emplace(std::in_place_index<I>, std::variant_alternative_t<I, NodeData>::read(j, reader))
        : (void)0),
   ...);
  return out;
}

struct DepthScope {
  explicit DepthScope(size_t& depth) : depth_(depth) { ++depth_; }
  ~DepthScope() { --depth_; }
  size_t& depth_;
};

}  // namespace

NodeIndex NodeReader::node(const JsonNode& j) {
  // node() and the composite nodes' readers recurse into each other: bound the depth before going down.
  if (depth_ == kMaxGraphNodeDepth)
    j.fail("nodes nest deeper than " + std::to_string(kMaxGraphNodeDepth) + " levels, the limit");
  const DepthScope scope(depth_);
  if (!j.isObject()) j.fail("expected a node object with a \"type\"");
  const std::string type = j.at("type").string();
  const std::string name = j.stringOr("name", "");
  constexpr auto kAlternatives = std::make_index_sequence<std::variant_size_v<NodeData>>();
  std::optional<NodeData> data = readAs(type, j, *this, kAlternatives);
  if (!data) j.at("type").fail("unknown node type '" + type + "' (expected " + typeList(kAlternatives) + ")");
  return builder_.add(std::move(*data), name, j.pointer());
}

ParameterIndex NodeReader::parameter(const JsonNode& j) const {
  const std::string name = j.string();
  auto p = builder_.findParameter(name);
  if (!p) j.fail("no parameter named '" + name + "'");
  return *p;
}

ParameterType NodeReader::parameterType(ParameterIndex p) const { return builder_.parameter(p).type; }

FloatInput NodeReader::floatInput(const JsonNode& parent, std::string_view key, float fallback) const {
  auto j = parent.find(key);
  if (!j) return FloatInput::fixed(fallback);
  if (j->isNumber()) return FloatInput::fixed(j->number());
  if (!j->isString()) j->fail("expected a number or a parameter name");
  return FloatInput::bound(parameter(*j));
}

EasingCurve NodeReader::curve(const JsonNode& parent) const {
  auto c = parent.find("curve");
  return c ? parseEasingCurve(*c) : EasingCurve::linear();
}

uint32_t NodeReader::timeline(const JsonNode& j) const {
  auto index = builder_.findTimeline(j.string());
  if (!index) j.fail("no timeline named '" + j.string() + "' in \"timelines\"");
  return *index;
}

const ChannelSet& NodeReader::channels() const { return builder_.channels(); }

}  // namespace facial::detail
