#include "editor/graph_document.h"

#include <cmath>
#include <fstream>

#include "engine/scene/file_bytes.h"
#include "facial/runtime/curves/easing_curve.h"

namespace editor {

namespace {

using facial::Json;

eng::Error problem(std::string_view text) { return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(text)); }

// Depth first under `node`: the pointer of the state machine named `name`
// ("" matches any), in `found`.
bool findMachine(const Json& node, const Json::json_pointer& at, std::string_view name, Json::json_pointer& found) {
  if (node.is_object()) {
    const auto type = node.find("type");
    if (type != node.end() && *type == "stateMachine" &&
        (name.empty() || (node.contains("name") && node["name"] == std::string(name)))) {
      found = at;
      return true;
    }
    for (auto it = node.begin(); it != node.end(); ++it)
      if (findMachine(it.value(), at / it.key(), name, found)) return true;
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      if (findMachine(node[i], at / i, name, found)) return true;
  }
  return false;
}

std::string stringOr(const Json& object, const char* key, std::string fallback = {}) {
  const auto it = object.find(key);
  return it != object.end() && it->is_string() ? it->get<std::string>() : fallback;
}

std::string easingName(const Json& transition) {
  const auto curve = transition.find("curve");
  if (curve == transition.end()) return "linear";
  if (curve->is_string()) return curve->get<std::string>();
  return stringOr(*curve, "type", "linear");
}

GraphTransitionInfo describeTransition(const Json& t, std::string from) {
  GraphTransitionInfo info;
  info.from = std::move(from);
  info.to = stringOr(t, "to");
  info.duration = t.value("duration", info.duration);
  info.easing = easingName(t);
  if (t.contains("exitTime") && t["exitTime"].is_number()) info.exitTime = t["exitTime"].get<float>();
  info.interruptible = t.value("interruptible", true);
  if (const auto conditions = t.find("conditions"); conditions != t.end() && conditions->is_array())
    for (const Json& c : *conditions)
      if (c.is_object() && c.size() == 1 && c.contains("parameter")) {
        info.trigger = stringOr(c, "parameter");
        break;
      }
  return info;
}

}  // namespace

eng::Result<void> checkTransitionTiming(float duration, std::string_view easing) {
  if (!std::isfinite(duration) || duration <= 0.0f)
    return problem("a transition's duration must be a finite number > 0 (got " + facial::formatNumber(duration) + ")");
  const auto type = facial::easingTypeFromName(easing);
  if (!type || (*type != facial::EasingType::Linear && *type != facial::EasingType::Cosine &&
                *type != facial::EasingType::Smoothstep))
    return problem("unknown easing '" + std::string(easing) + "' (linear, cosine, smoothstep)");
  return {};
}

namespace {

// Removes the transitions to `state` from one list.
void dropTransitionsTo(Json& list, std::string_view state) {
  if (!list.is_array()) return;
  for (size_t i = list.size(); i-- > 0;)
    if (stringOr(list[i], "to") == state) list.erase(i);
}

}  // namespace

eng::Result<GraphDocument> GraphDocument::fromJson(Json document, std::string source) {
  GraphDocument doc;
  const auto root = document.find("root");
  if (root == document.end() || !(findMachine(*root, Json::json_pointer("/root"), "emotions", doc.machinePointer_) ||
                                  findMachine(*root, Json::json_pointer("/root"), "", doc.machinePointer_)))
    return eng::makeError(eng::ErrorKind::Malformed, source + ": the graph has no state machine to edit");
  const Json& states = document.at(doc.machinePointer_).value("states", Json());
  if (!states.is_array() || states.empty())
    return eng::makeError(eng::ErrorKind::Malformed, source + ": " + doc.machinePointer_.to_string() + ": no states");
  doc.document_ = std::move(document);
  doc.source_ = std::move(source);
  return doc;
}

eng::Result<GraphDocument> GraphDocument::load(const std::filesystem::path& path) {
  auto json = facial::readJsonFile(path);
  if (!json) return json.error();
  return fromJson(std::move(*json), path.string());
}

std::vector<GraphStateInfo> GraphDocument::states() const {
  std::vector<GraphStateInfo> out;
  for (const Json& s : machine()["states"]) {
    GraphStateInfo info{stringOr(s, "name"), {}};
    if (const auto node = s.find("node"); node != s.end() && node->is_object() && stringOr(*node, "type") == "pose")
      info.expression = stringOr(*node, "preset");
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<GraphTransitionInfo> GraphDocument::transitions() const {
  std::vector<GraphTransitionInfo> out;
  for (const Json& s : machine()["states"])
    if (const auto list = s.find("transitions"); list != s.end() && list->is_array())
      for (const Json& t : *list) out.push_back(describeTransition(t, stringOr(s, "name")));
  if (const auto any = machine().find("anyState"); any != machine().end() && any->is_array())
    for (const Json& t : *any) out.push_back(describeTransition(t, std::string(kAnyState)));
  return out;
}

std::optional<GraphTransitionInfo> GraphDocument::findTransition(std::string_view from, std::string_view to) const {
  for (GraphTransitionInfo& t : transitions())
    if (t.from == from && t.to == to) return std::move(t);
  return std::nullopt;
}

std::string GraphDocument::defaultState() const {
  const std::string named = stringOr(machine(), "defaultState");
  return named.empty() ? stringOr(machine()["states"][0], "name") : named;
}

bool GraphDocument::hasState(std::string_view name) const {
  for (const Json& s : machine()["states"])
    if (stringOr(s, "name") == name) return true;
  return false;
}

Json* GraphDocument::transitionList(std::string_view from) {
  Json& m = machine();
  if (from == kAnyState) {
    if (!m.contains("anyState")) m["anyState"] = Json::array();
    return &m["anyState"];
  }
  for (Json& s : m["states"])
    if (stringOr(s, "name") == from) {
      if (!s.contains("transitions")) s["transitions"] = Json::array();
      return &s["transitions"];
    }
  return nullptr;
}

Json* GraphDocument::findTransitionJson(std::string_view from, std::string_view to) {
  Json* list = transitionList(from);
  if (!list || !list->is_array()) return nullptr;
  for (Json& t : *list)
    if (stringOr(t, "to") == to) return &t;
  return nullptr;
}

eng::Result<void> GraphDocument::checkNewStateName(std::string_view name) const {
  if (name.empty() || name == kAnyState) return problem("'" + std::string(name) + "' cannot name a state");
  if (hasState(name)) return problem("there is already a state '" + std::string(name) + "'");
  return {};
}

eng::Result<void> GraphDocument::declareTrigger(std::string_view trigger) {
  if (!document_.contains("parameters")) document_["parameters"] = Json::array();
  for (const Json& p : document_["parameters"])
    if (stringOr(p, "name") == trigger) {
      if (stringOr(p, "type") == "trigger") return {};
      return problem("parameter '" + std::string(trigger) + "' is a " + stringOr(p, "type") + ", not a trigger");
    }
  document_["parameters"].push_back({{"name", std::string(trigger)}, {"type", "trigger"}});
  return {};
}

void GraphDocument::commit(Snapshot before) {
  undo_.push_back(std::move(before));
  redo_.clear();
  revision_ = nextRevision_++;
}

eng::Result<void> GraphDocument::addState(std::string_view name, std::string_view expression) {
  ENG_TRY(checkNewStateName(name));
  if (expression.empty()) return problem("state '" + std::string(name) + "' needs an expression (a preset name)");
  Snapshot before = snapshot();
  machine()["states"].push_back(
      {{"name", std::string(name)}, {"node", {{"type", "pose"}, {"preset", std::string(expression)}}}});
  commit(std::move(before));
  return {};
}

eng::Result<void> GraphDocument::removeState(std::string_view name) {
  if (!hasState(name)) return problem("no state '" + std::string(name) + "'");
  Json& states = machine()["states"];
  if (states.size() == 1) return problem("'" + std::string(name) + "' is the only state: a state machine needs one");
  Snapshot before = snapshot();
  for (size_t i = states.size(); i-- > 0;)
    if (stringOr(states[i], "name") == name) states.erase(i);
  for (Json& s : states)
    if (s.contains("transitions")) dropTransitionsTo(s["transitions"], name);
  if (machine().contains("anyState")) dropTransitionsTo(machine()["anyState"], name);
  if (stringOr(machine(), "defaultState") == name) machine().erase("defaultState");
  commit(std::move(before));
  return {};
}

eng::Result<void> GraphDocument::renameState(std::string_view from, std::string_view to) {
  if (!hasState(from)) return problem("no state '" + std::string(from) + "'");
  ENG_TRY(checkNewStateName(to));
  Snapshot before = snapshot();
  const auto renameIn = [&](Json& list) {
    for (Json& t : list)
      if (stringOr(t, "to") == from) t["to"] = std::string(to);
  };
  for (Json& s : machine()["states"]) {
    if (stringOr(s, "name") == from) s["name"] = std::string(to);
    if (s.contains("transitions")) renameIn(s["transitions"]);
  }
  if (machine().contains("anyState")) renameIn(machine()["anyState"]);
  if (stringOr(machine(), "defaultState") == from) machine()["defaultState"] = std::string(to);
  commit(std::move(before));
  return {};
}

eng::Result<void> GraphDocument::addTransition(std::string_view from, std::string_view to, std::string_view trigger,
                                               float duration, std::string_view easing) {
  if (from != kAnyState && !hasState(from)) return problem("no state '" + std::string(from) + "' to start from");
  if (!hasState(to)) return problem("no state '" + std::string(to) + "' to go to");
  if (from == to) return problem("a state's transition to itself is not supported here ('" + std::string(from) + "')");
  ENG_TRY(checkTransitionTiming(duration, easing));
  if (findTransitionJson(from, to))
    return problem("there is already a transition " + std::string(from) + " -> " + std::string(to));
  Snapshot before = snapshot();
  Json transition = {{"to", std::string(to)}, {"duration", duration}, {"curve", std::string(easing)}};
  if (!trigger.empty() && trigger != "-") {
    if (auto declared = declareTrigger(trigger); !declared) {
      document_ = std::move(before.document);
      return declared;
    }
    transition["conditions"] = Json::array({{{"parameter", std::string(trigger)}}});
  }
  transitionList(from)->push_back(std::move(transition));
  commit(std::move(before));
  return {};
}

eng::Result<void> GraphDocument::editTransition(std::string_view from, std::string_view to, float duration,
                                                std::string_view easing, std::optional<float> exitTime,
                                                bool interruptible) {
  ENG_TRY(checkTransitionTiming(duration, easing));
  if (exitTime && (!std::isfinite(*exitTime) || *exitTime < 0.0f))
    return problem("exit time must be a finite number >= 0 (got " + facial::formatNumber(*exitTime) + ")");
  Snapshot before = snapshot();
  Json* t = findTransitionJson(from, to);
  if (!t) {
    document_ = std::move(before.document);  // transitionList() may have added an empty list
    return problem("no transition " + std::string(from) + " -> " + std::string(to));
  }
  (*t)["duration"] = duration;
  (*t)["curve"] = std::string(easing);
  if (exitTime)
    (*t)["exitTime"] = *exitTime;
  else
    t->erase("exitTime");
  if (interruptible)
    t->erase("interruptible");
  else
    (*t)["interruptible"] = false;
  commit(std::move(before));
  return {};
}

eng::Result<void> GraphDocument::removeTransition(std::string_view from, std::string_view to) {
  Snapshot before = snapshot();
  Json* list = transitionList(from);
  if (!list || !findTransitionJson(from, to)) {
    document_ = std::move(before.document);
    return problem("no transition " + std::string(from) + " -> " + std::string(to));
  }
  for (size_t i = 0; i < list->size(); ++i)
    if (stringOr((*list)[i], "to") == to) {
      list->erase(i);
      break;
    }
  commit(std::move(before));
  return {};
}

bool GraphDocument::step(std::vector<Snapshot>& from, std::vector<Snapshot>& to) {
  if (from.empty()) return false;
  to.push_back(snapshot());
  document_ = std::move(from.back().document);
  revision_ = from.back().revision;
  from.pop_back();
  return true;
}

bool GraphDocument::undo() { return step(undo_, redo_); }
bool GraphDocument::redo() { return step(redo_, undo_); }

void GraphDocument::discardLast() {
  if (undo()) redo_.pop_back();
}

eng::Result<void> GraphDocument::writeCopy(const std::filesystem::path& path) const {
  const std::string text = document_.dump(2) + "\n";
  return eng::writeFileWhole(path, [&](const std::filesystem::path& partial) -> eng::Result<void> {
    return eng::writeFileBytes(partial, text.data(), text.size());
  });
}

eng::Result<void> GraphDocument::save(const std::filesystem::path& path) {
  ENG_TRY(writeCopy(path));
  savedRevision_ = revision_;
  return {};
}

}  // namespace editor
