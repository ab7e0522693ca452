#include "facial/runtime/graph/graph_json.h"

#include "engine/core/confined_path.h"
#include "facial/runtime/graph/detail/json_reader.h"
#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/timeline_json.h"

namespace facial {
using detail::NodeReader;

namespace {

// Reads the graph's parameters and timelines into the builder; the nodes
// are read by NodeReader (each node type by its own read()). Semantic checks
// stay in the builder, which reports them at the nodes' JSON pointers.
class GraphParser {
 public:
  GraphParser(GraphBuilder& builder, std::filesystem::path folder, bool allowOutsidePaths)
      : builder_(builder), folder_(std::move(folder)), allowOutsidePaths_(allowOutsidePaths) {}

  eng::Result<void> parameters(const JsonNode& list) {
    const size_t count = ENG_TRY_VALUE(list.size());
    for (size_t i = 0; i < count; ++i) ENG_TRY(parameter(list.element(i)));
    return {};
  }

  eng::Result<void> timelines(const JsonNode& map) {
    if (!map.isObject()) return map.error("expected an object {\"name\": path or timeline}");
    for (const auto& [name, entry] : ENG_TRY_VALUE(map.members())) {
      if (entry.isString()) {
        builder_.addTimeline(ENG_TRY_VALUE(timelineFile(entry, name)));
      } else {
        builder_.addTimeline(ENG_TRY_VALUE(detail::parseTimeline(entry, std::string(name))));
      }
    }
    return {};
  }

 private:
  eng::Result<Timeline> timelineFile(const JsonNode& entry, std::string_view name) const {
    const std::string file = ENG_TRY_VALUE(entry.string());
    auto path = allowOutsidePaths_ ? eng::Result<std::filesystem::path>(folder_ / file)
                                   : eng::resolveInsideFolder(folder_, file);
    if (!path) return entry.error(path.error().message + " (a graph's files stay in its folder)", path.error().kind);
    auto timeline = loadTimeline(*path);
    // Only the kind: the message may quote the other file (its keys, its text).
    if (!timeline && timeline.error().kind == eng::ErrorKind::NotFound)
      return entry.error("timeline file '" + file + "' not found", eng::ErrorKind::NotFound);
    if (!timeline)
      return entry.error("timeline file '" + file + "' did not load (" + std::string(eng::errorKindName(timeline.error().kind)) +
                             "); load it on its own to see why",
                         timeline.error().kind);
    timeline->name = name;
    return timeline;
  }

  eng::Result<void> parameter(const JsonNode& p) {
    ENG_TRY(p.allowOnly({"name", "type", "default"}));
    const JsonNode nameNode = ENG_TRY_VALUE(p.at("name"));
    const std::string name = ENG_TRY_VALUE(nameNode.string());
    if (builder_.findParameter(name)) return nameNode.error("parameter '" + name + "' is declared twice");
    auto type = parameterTypeFromName(ENG_TRY_VALUE(p.stringOr("type", "float")));
    if (!type) return ENG_TRY_VALUE(p.at("type")).error("unknown parameter type (expected " + eng::nameList(kParameterTypeNames) + ")");
    float value = 0.0f;
    if (auto d = p.find("default")) {
      if (*type == ParameterType::Trigger) return d->error("a trigger has no default (it starts cleared)");
      value = *type == ParameterType::Bool ? (ENG_TRY_VALUE(d->boolean()) ? 1.0f : 0.0f) : ENG_TRY_VALUE(d->number());
    }
    builder_.addParameter(name, *type, value);
    return {};
  }

  GraphBuilder& builder_;
  std::filesystem::path folder_;
  bool allowOutsidePaths_ = false;
};

eng::Result<ChannelSet> channelSet(const JsonNode& j) {
  if (j.isString()) {
    const std::string name = ENG_TRY_VALUE(j.string());
    if (name == "actionUnitsAndVisemes") return ChannelSet::actionUnitsAndVisemes();
    if (name != "actionUnits")
      return j.error("unknown channel set '" + name + "' (expected \"actionUnits\", \"actionUnitsAndVisemes\" or a list of names)");
    return ChannelSet::actionUnits();
  }
  const size_t count = ENG_TRY_VALUE(j.size());
  std::vector<std::string> names;
  for (size_t i = 0; i < count; ++i) names.push_back(ENG_TRY_VALUE(j.element(i).string()));
  auto set = ChannelSet::fromNames(names);
  if (!set) return j.error(set.error().message);
  return set;
}

eng::Result<SharedGraphDefinition> readGraph(const JsonNode& root, const std::filesystem::path& source,
                                             const GraphLoadOptions& options) {
  ENG_TRY(requireVersion(root, kGraphFileVersion));
  ENG_TRY(root.allowOnly({"version", "channels", "parameters", "timelines", "root"}));
  ENG_TRY(detail::checkNumberRange(root));  // before any field is read
  GraphBuilder builder(ENG_TRY_VALUE(channelSet(ENG_TRY_VALUE(root.at("channels")))), options.maxBytes);
  GraphParser parser(builder, source.parent_path(), options.allowOutsidePaths);
  if (auto p = root.find("parameters")) ENG_TRY(parser.parameters(*p));
  if (auto t = root.find("timelines")) ENG_TRY(parser.timelines(*t));
  NodeReader nodes(builder, options.presets);
  builder.setRoot(ENG_TRY_VALUE(nodes.node(ENG_TRY_VALUE(root.at("root")))));
  return builder.build();
}

}  // namespace

eng::Result<SharedGraphDefinition> parseGraph(const Json& document, const std::filesystem::path& source,
                                              const GraphLoadOptions& options) {
  auto graph = readGraph(JsonNode(document, ""), source, options);
  if (!graph) return graph.error().prefixed(source.string() + ": ");
  return graph;
}

eng::Result<SharedGraphDefinition> loadGraph(const std::filesystem::path& path, const GraphLoadOptions& options) {
  auto document = readJsonFile(path);
  if (!document) return document.error();
  return parseGraph(*document, path, options);
}

}  // namespace facial
