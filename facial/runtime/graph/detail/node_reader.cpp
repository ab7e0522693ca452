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
std::optional<eng::Result<NodeData>> readAs(std::string_view type, const JsonNode& j, NodeReader& reader,
                                            std::index_sequence<I...>) {
  std::optional<eng::Result<NodeData>> out;
  auto readOne = [&]<size_t K>(std::integral_constant<size_t, K>) {
    using Alternative = std::variant_alternative_t<K, NodeData>;
    if (Alternative::kType != type) return;
    auto data = Alternative::read(j, reader);
    if (!data) out.emplace(data.error());
    else out.emplace(NodeData(std::in_place_index<K>, std::move(data).value()));
  };
  (readOne(std::integral_constant<size_t, I>{}), ...);
  return out;
}

struct DepthScope {
  explicit DepthScope(size_t& depth) : depth_(depth) { ++depth_; }
  ~DepthScope() { --depth_; }
  size_t& depth_;
};

}  // namespace

eng::Result<NodeIndex> NodeReader::node(const JsonNode& j) {
  // node() and the composite nodes' readers recurse into each other: bound the depth before going down.
  if (depth_ == kMaxGraphNodeDepth)
    return j.error("nodes nest deeper than " + std::to_string(kMaxGraphNodeDepth) + " levels, the limit");
  const DepthScope scope(depth_);
  if (!j.isObject()) return j.error("expected a node object with a \"type\"");
  const JsonNode typeNode = ENG_TRY_VALUE(j.at("type"));
  const std::string type = ENG_TRY_VALUE(typeNode.string());
  const std::string name = ENG_TRY_VALUE(j.stringOr("name", ""));
  constexpr auto kAlternatives = std::make_index_sequence<std::variant_size_v<NodeData>>();
  std::optional<eng::Result<NodeData>> data = readAs(type, j, *this, kAlternatives);
  if (!data) return typeNode.error("unknown node type '" + type + "' (expected " + typeList(kAlternatives) + ")");
  if (!*data) return data->error();
  const NodeIndex index = builder_.add(std::move(**data), name, j.pointer());
  if (builder_.budgetError()) return *builder_.budgetError();  // stop reading at once
  return index;
}

eng::Result<ParameterIndex> NodeReader::parameter(const JsonNode& j) const {
  const std::string name = ENG_TRY_VALUE(j.string());
  auto p = builder_.findParameter(name);
  if (!p) return j.error("no parameter named '" + name + "'");
  return *p;
}

ParameterType NodeReader::parameterType(ParameterIndex p) const { return builder_.parameter(p).type; }

eng::Result<FloatInput> NodeReader::floatInput(const JsonNode& parent, std::string_view key, float fallback) const {
  auto j = parent.find(key);
  if (!j) return FloatInput::fixed(fallback);
  if (j->isNumber()) return FloatInput::fixed(ENG_TRY_VALUE(j->number()));
  if (!j->isString()) return j->error("expected a number or a parameter name");
  return FloatInput::bound(ENG_TRY_VALUE(parameter(*j)));
}

eng::Result<EasingCurve> NodeReader::curve(const JsonNode& parent) const {
  auto c = parent.find("curve");
  return c ? parseEasingCurve(*c) : eng::Result<EasingCurve>(EasingCurve::linear());
}

eng::Result<uint32_t> NodeReader::timeline(const JsonNode& j) const {
  const std::string name = ENG_TRY_VALUE(j.string());
  auto index = builder_.findTimeline(name);
  if (!index) return j.error("no timeline named '" + name + "' in \"timelines\"");
  return *index;
}

const ChannelSet& NodeReader::channels() const { return builder_.channels(); }

}  // namespace facial::detail
