#include "facial/runtime/graph/graph_json.h"

#include "facial/runtime/graph/detail/json_reader.h"
#include "facial/runtime/graph/detail/node_reader.h"
#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/timeline_json.h"

namespace facial {
// The throwing readers; parseGraph turns their JsonProblem into an eng::Error.
using namespace detail;

namespace {

// Reads the graph's parameters and timelines into the builder; the nodes
// are read by NodeReader (each node type by its own read()). Semantic checks
// stay in the builder, which reports them at the nodes' JSON pointers.
class GraphParser {
 public:
  GraphParser(GraphBuilder& builder, std::filesystem::path folder) : builder_(builder), folder_(std::move(folder)) {}

  void parameters(const JsonNode& list) {
    for (size_t i = 0; i < list.size(); ++i) {
      const JsonNode p = list[i];
      p.allowOnly({"name", "type", "default"});
      const std::string name = p.at("name").string();
      if (builder_.findParameter(name)) p.at("name").fail("parameter '" + name + "' is declared twice");
      auto type = parameterTypeFromString(p.stringOr("type", "float"));
      if (!type) p.at("type").fail("unknown parameter type (expected float, bool or trigger)");
      float value = 0.0f;
      if (auto d = p.find("default")) {
        if (*type == ParameterType::Trigger) d->fail("a trigger has no default (it starts cleared)");
        value = *type == ParameterType::Bool ? (d->boolean() ? 1.0f : 0.0f) : d->number();
      }
      builder_.addParameter(name, *type, value);
    }
  }

  void timelines(const JsonNode& map) {
    if (!map.isObject()) map.fail("expected an object {\"name\": path or timeline}");
    for (auto it = map.raw().begin(); it != map.raw().end(); ++it) {
      const JsonNode entry = map.at(it.key());
      if (entry.isString()) {
        const std::filesystem::path file = folder_ / entry.string();
        auto timeline = loadTimeline(file);
        if (!timeline) entry.fail(timeline.error());
        timeline->name = it.key();
        builder_.addTimeline(std::move(timeline).value());
      } else {
        builder_.addTimeline(parseTimeline(entry, it.key()));
      }
    }
  }

 private:
  GraphBuilder& builder_;
  std::filesystem::path folder_;
};

ChannelSet channelSet(const JsonNode& j) {
  if (j.isString()) {
    if (j.string() != "actionUnits") j.fail("unknown channel set '" + j.string() + "' (expected \"actionUnits\" or a list of names)");
    return ChannelSet::actionUnits();
  }
  std::vector<std::string> names;
  for (size_t i = 0; i < j.size(); ++i) names.push_back(j[i].string());
  auto set = ChannelSet::fromNames(names);
  if (!set) j.fail(set.error().message);
  return std::move(set).value();
}

}  // namespace

eng::Result<SharedGraphDefinition> parseGraph(const Json& document, const std::filesystem::path& source,
                                              const GraphLoadOptions& options) {
  try {
    const JsonNode root(document, "");
    requireVersion(root, kGraphFileVersion);
    root.allowOnly({"version", "channels", "parameters", "timelines", "root"});
    GraphBuilder builder(channelSet(root.at("channels")));
    GraphParser parser(builder, source.parent_path());
    if (auto p = root.find("parameters")) parser.parameters(*p);
    if (auto t = root.find("timelines")) parser.timelines(*t);
    NodeReader nodes(builder, options.presets);
    builder.setRoot(nodes.node(root.at("root")));
    auto graph = builder.build();
    if (!graph) return graph.error().prefixed(source.string() + ": ");
    return graph;
  } catch (const JsonProblem& p) {
    return jsonProblemError(p, source.string());
  }
}

eng::Result<SharedGraphDefinition> loadGraph(const std::filesystem::path& path, const GraphLoadOptions& options) {
  auto document = readJsonFile(path);
  if (!document) return document.error();
  return parseGraph(*document, path, options);
}

}  // namespace facial
