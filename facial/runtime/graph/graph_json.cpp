#include "facial/runtime/graph/graph_json.h"

#include "facial/runtime/graph/detail/json_reader.h"
#include "facial/runtime/graph/graph_builder.h"
#include "facial/runtime/graph/timeline_json.h"

namespace facial {
// The throwing readers; parseGraph turns their JsonProblem into an eng::Error.
using namespace detail;

namespace {

// Turns the JSON tree into builder calls; semantic checks stay in the
// builder, which reports them at the nodes' JSON pointers.
class GraphParser {
 public:
  GraphParser(GraphBuilder& builder, const GraphLoadOptions& options, std::filesystem::path folder)
      : builder_(builder), options_(options), folder_(std::move(folder)) {}

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

  NodeIndex node(const JsonNode& j) {
    // node() and the composite nodes recurse into each other: bound the depth before going down.
    if (depth_ == kMaxGraphNodeDepth)
      j.fail("nodes nest deeper than " + std::to_string(kMaxGraphNodeDepth) + " levels, the limit");
    const DepthScope scope(depth_);
    if (!j.isObject()) j.fail("expected a node object with a \"type\"");
    const std::string type = j.at("type").string();
    const std::string name = j.stringOr("name", "");
    if (type == "pose") return add(pose(j), name, j);
    if (type == "blend") return add(blend(j), name, j);
    if (type == "bilinear") return add(bilinear(j), name, j);
    if (type == "controlMap") return add(controlMap(j), name, j);
    if (type == "freeformMap") return add(freeformMap(j), name, j);
    if (type == "additive") return add(additive(j), name, j);
    if (type == "timeline") return add(timeline(j), name, j);
    if (type == "stateMachine") return add(stateMachine(j), name, j);
    if (type == "blink") return add(blink(j), name, j);
    j.at("type").fail("unknown node type '" + type +
                      "' (expected pose, blend, bilinear, controlMap, freeformMap, additive, timeline, "
                      "stateMachine or blink)");
  }

 private:
  struct DepthScope {
    explicit DepthScope(size_t& depth) : depth_(depth) { ++depth_; }
    ~DepthScope() { --depth_; }
    size_t& depth_;
  };

  NodeIndex add(NodeData data, const std::string& name, const JsonNode& j) {
    return builder_.add(std::move(data), name, j.pointer());
  }

  ParameterIndex parameter(const JsonNode& j) {
    const std::string name = j.string();
    auto p = builder_.findParameter(name);
    if (!p) j.fail("no parameter named '" + name + "'");
    return *p;
  }

  FloatInput floatInput(const JsonNode& parent, std::string_view key, float fallback) {
    auto j = parent.find(key);
    if (!j) return FloatInput::fixed(fallback);
    if (j->isNumber()) return FloatInput::fixed(j->number());
    if (!j->isString()) j->fail("expected a number or a parameter name");
    return FloatInput::bound(parameter(*j));
  }

  EasingCurve curve(const JsonNode& parent) {
    auto c = parent.find("curve");
    return c ? parseEasingCurve(*c) : EasingCurve::linear();
  }

  PoseNode pose(const JsonNode& j) {
    j.allowOnly({"type", "name", "preset", "intensity", "weights", "scale", "overrideBlink"});
    PoseNode node;
    const uint32_t channels = builder_.channels().size();
    if (auto preset = j.find("preset")) {
      if (j.has("weights")) j.fail("give either \"preset\" or \"weights\", not both");
      auto weights = presetPose(options_.presets, preset->string(), j.numberOr("intensity", 1.0f), builder_.channels());
      if (!weights) preset->fail(weights.error().message);
      node.weights = std::move(weights).value();
    } else if (auto w = j.find("weights")) {
      if (j.has("intensity")) j.at("intensity").fail("\"intensity\" applies to a preset; scale weights with \"scale\"");
      node.weights.assign(channels, 0.0f);
      if (w->isArray()) {
        if (w->size() != channels)
          w->fail("has " + std::to_string(w->size()) + " weights, the graph has " + std::to_string(channels) +
                  " channels");
        for (size_t c = 0; c < channels; ++c) node.weights[c] = (*w)[c].number();
      } else {
        if (!w->isObject()) w->fail("expected {\"channel\": weight} or an array of weights");
        for (auto it = w->raw().begin(); it != w->raw().end(); ++it) {
          auto c = builder_.channels().find(it.key());
          if (!c) w->at(it.key()).fail("'" + it.key() + "' is not a channel of this graph");
          node.weights[*c] = w->at(it.key()).number();
        }
      }
    } else {
      j.fail("a pose needs \"preset\" or \"weights\"");
    }
    node.scale = floatInput(j, "scale", 1.0f);
    if (auto o = j.find("overrideBlink")) {
      auto mode = vrmOverrideFromString(o->string());
      if (!mode) o->fail("unknown overrideBlink (expected none, block or blend)");
      node.overrideBlink = *mode;
    }
    return node;
  }

  BlendNode blend(const JsonNode& j) {
    j.allowOnly({"type", "name", "a", "b", "factor", "curve"});
    BlendNode b{.a = node(j.at("a")), .b = node(j.at("b"))};
    b.factor = floatInput(j, "factor", 0.0f);
    b.curve = curve(j);
    return b;
  }

  BilinearNode bilinear(const JsonNode& j) {
    j.allowOnly({"type", "name", "shapes", "shape", "expression", "duration", "curve"});
    BilinearNode b;
    const JsonNode shapes = j.at("shapes");
    if (shapes.size() != 2) shapes.fail("expected two rows (face shapes), got " + std::to_string(shapes.size()));
    for (size_t s = 0; s < 2; ++s) {
      std::vector<NodeIndex>& row = s == 0 ? b.shape1 : b.shape2;
      for (size_t e = 0; e < shapes[s].size(); ++e) row.push_back(node(shapes[s][e]));
    }
    b.shape = floatInput(j, "shape", 0.0f);
    b.expression = parameter(j.at("expression"));
    b.duration = j.numberOr("duration", b.duration);
    b.curve = curve(j);
    return b;
  }

  ControlMapNode controlMap(const JsonNode& j) {
    j.allowOnly({"type", "name", "neutral", "up", "down", "right", "left", "x", "y"});
    ControlMapNode m{.neutral = node(j.at("neutral")),
                     .e1 = node(j.at("up")),
                     .e2 = node(j.at("down")),
                     .e3 = node(j.at("right")),
                     .e4 = node(j.at("left"))};
    m.x = floatInput(j, "x", 0.0f);
    m.y = floatInput(j, "y", 0.0f);
    return m;
  }

  FreeformMapNode freeformMap(const JsonNode& j) {
    j.allowOnly({"type", "name", "neutral", "poles", "x", "y"});
    FreeformMapNode m;
    m.neutral = node(j.at("neutral"));
    const JsonNode poles = j.at("poles");
    for (size_t i = 0; i < poles.size(); ++i) {
      const JsonNode p = poles[i];
      p.allowOnly({"at", "node"});
      const JsonNode at = p.at("at");
      if (at.size() != 2) at.fail("expected [x, y]");
      m.poles.push_back({{at[0].number(), at[1].number()}, node(p.at("node"))});
    }
    m.x = floatInput(j, "x", 0.0f);
    m.y = floatInput(j, "y", 0.0f);
    return m;
  }

  AdditiveNode additive(const JsonNode& j) {
    j.allowOnly({"type", "name", "base", "layer", "weight", "mask"});
    AdditiveNode a{.base = node(j.at("base")), .layer = node(j.at("layer"))};
    a.weight = floatInput(j, "weight", 1.0f);
    if (auto mask = j.find("mask")) {
      mask->allowOnly({"region", "side"});
      const std::string region = mask->stringOr("region", "any");
      if (region == "upper") a.mask.region = FaceRegion::Upper;
      else if (region == "lower") a.mask.region = FaceRegion::Lower;
      else if (region != "any") mask->at("region").fail("unknown region (expected any, upper or lower)");
      const std::string side = mask->stringOr("side", "any");
      if (side == "left") a.mask.side = FaceSide::Left;
      else if (side == "right") a.mask.side = FaceSide::Right;
      else if (side == "both") a.mask.side = FaceSide::Both;
      else if (side != "any") mask->at("side").fail("unknown side (expected any, left, right or both)");
    }
    return a;
  }

  TimelineNode timeline(const JsonNode& j) {
    j.allowOnly({"type", "name", "timeline", "loop", "speed"});
    TimelineNode t;
    const JsonNode name = j.at("timeline");
    auto index = builder_.findTimeline(name.string());
    if (!index) name.fail("no timeline named '" + name.string() + "' in \"timelines\"");
    t.timeline = *index;
    if (auto loop = j.find("loop")) {
      auto mode = loopModeFromString(loop->string());
      if (!mode) loop->fail("unknown loop mode (expected once, clamp, loop or pingpong)");
      t.loop = *mode;
    }
    t.speed = floatInput(j, "speed", 1.0f);
    return t;
  }

  TransitionCondition condition(const JsonNode& j) {
    j.allowOnly({"parameter", "op", "value"});
    TransitionCondition c;
    c.parameter = parameter(j.at("parameter"));
    switch (builder_.parameter(c.parameter).type) {
      case ParameterType::Trigger:
        if (j.has("op") || j.has("value")) j.fail("a trigger condition takes only \"parameter\"");
        c.op = ConditionOp::Triggered;
        break;
      case ParameterType::Bool:
        if (j.has("op")) j.at("op").fail("a bool condition takes \"value\": true or false");
        c.op = j.booleanOr("value", true) ? ConditionOp::IsTrue : ConditionOp::IsFalse;
        break;
      case ParameterType::Float: {
        const JsonNode op = j.at("op");
        auto parsed = conditionOpFromString(op.string());
        if (!parsed || *parsed == ConditionOp::IsTrue || *parsed == ConditionOp::IsFalse ||
            *parsed == ConditionOp::Triggered)
          op.fail("unknown comparison '" + op.string() + "' (expected >, >=, <, <=, == or !=)");
        c.op = *parsed;
        c.threshold = j.at("value").number();
        break;
      }
    }
    return c;
  }

  std::vector<Transition> transitions(const JsonNode& list) {
    std::vector<Transition> out;
    for (size_t i = 0; i < list.size(); ++i) {
      const JsonNode j = list[i];
      j.allowOnly({"to", "duration", "curve", "exitTime", "priority", "interruptible", "canTransitionToSelf",
                   "conditions"});
      Transition t;
      t.to = j.at("to").string();
      t.duration = j.numberOr("duration", t.duration);
      t.curve = curve(j);
      if (auto e = j.find("exitTime")) t.exitTime = e->number();
      if (auto p = j.find("priority")) {
        if (!p->raw().is_number_integer()) p->fail("expected an integer, got " + p->raw().dump());
        t.priority = p->raw().get<int>();
      }
      t.interruptible = j.booleanOr("interruptible", true);
      t.canTransitionToSelf = j.booleanOr("canTransitionToSelf", false);
      if (auto conditions = j.find("conditions"))
        for (size_t c = 0; c < conditions->size(); ++c) t.conditions.push_back(condition((*conditions)[c]));
      out.push_back(std::move(t));
    }
    return out;
  }

  StateMachineNode stateMachine(const JsonNode& j) {
    j.allowOnly({"type", "name", "states", "anyState", "defaultState"});
    StateMachineNode m;
    const JsonNode states = j.at("states");
    for (size_t i = 0; i < states.size(); ++i) {
      const JsonNode s = states[i];
      s.allowOnly({"name", "node", "transitions"});
      MachineState state{.name = s.at("name").string(), .node = node(s.at("node"))};
      if (auto t = s.find("transitions")) state.transitions = transitions(*t);
      m.states.push_back(std::move(state));
    }
    if (auto any = j.find("anyState")) m.anyState = transitions(*any);
    m.defaultState = j.stringOr("defaultState", "");
    return m;
  }

  BlinkNode blink(const JsonNode& j) {
    j.allowOnly({"type", "name", "input", "channels", "wideChannels", "amount", "minInterval", "maxInterval",
                 "closeDuration", "closedDuration", "openDuration", "doubleBlinkChance", "doubleBlinkGap",
                 "wideStart", "wideFull"});
    BlinkNode b;
    b.input = node(j.at("input"));
    auto names = [&](std::string_view key) {
      std::vector<std::string> out;
      if (auto list = j.find(key))
        for (size_t i = 0; i < list->size(); ++i) out.push_back((*list)[i].string());
      return out;
    };
    b.channels = names("channels");
    b.wideChannels = names("wideChannels");
    b.amount = floatInput(j, "amount", 1.0f);
    b.minInterval = j.numberOr("minInterval", b.minInterval);
    b.maxInterval = j.numberOr("maxInterval", b.maxInterval);
    b.closeDuration = j.numberOr("closeDuration", b.closeDuration);
    b.closedDuration = j.numberOr("closedDuration", b.closedDuration);
    b.openDuration = j.numberOr("openDuration", b.openDuration);
    b.doubleBlinkChance = j.numberOr("doubleBlinkChance", b.doubleBlinkChance);
    b.doubleBlinkGap = j.numberOr("doubleBlinkGap", b.doubleBlinkGap);
    b.wideStart = j.numberOr("wideStart", b.wideStart);
    b.wideFull = j.numberOr("wideFull", b.wideFull);
    return b;
  }

  GraphBuilder& builder_;
  const GraphLoadOptions& options_;
  std::filesystem::path folder_;
  size_t depth_ = 0;  // node() calls under way
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
    GraphParser parser(builder, options, source.parent_path());
    if (auto p = root.find("parameters")) parser.parameters(*p);
    if (auto t = root.find("timelines")) parser.timelines(*t);
    builder.setRoot(parser.node(root.at("root")));
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
