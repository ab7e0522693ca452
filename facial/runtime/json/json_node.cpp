#include "facial/runtime/json/json_node.h"

#include <cassert>
#include <cmath>

namespace facial {

eng::Error JsonNode::error(std::string_view problem, eng::ErrorKind kind) const {
  std::string message = pointer_.empty() ? std::string("/") : pointer_;
  message += ": ";
  message += problem;
  return eng::makeError(kind, std::move(message));
}

eng::Error JsonNode::typeError(std::string_view expected) const {
  return error("expected " + std::string(expected) + ", got " + std::string(jsonTypeName(*value_)));
}

bool JsonNode::has(std::string_view key) const { return value_->is_object() && value_->contains(key); }

eng::Result<JsonNode> JsonNode::at(std::string_view key) const {
  if (!value_->is_object()) return typeError("an object");
  auto it = value_->find(key);
  if (it == value_->end()) return error("missing \"" + std::string(key) + "\"");
  return JsonNode(*it, childPath(pointer_, key));
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return JsonNode(*value_->find(key), childPath(pointer_, key));
}

eng::Result<void> JsonNode::allowOnly(std::initializer_list<std::string_view> known) const {
  if (!value_->is_object()) return typeError("an object");
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || k == it.key();
    if (ok) continue;
    std::string list;
    for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    return JsonNode(*it, childPath(pointer_, it.key())).error("unknown key (expected one of: " + list + ")");
  }
  return {};
}

eng::Result<std::vector<std::pair<std::string_view, JsonNode>>> JsonNode::members() const {
  if (!value_->is_object()) return typeError("an object");
  std::vector<std::pair<std::string_view, JsonNode>> out;
  out.reserve(value_->size());
  for (auto it = value_->begin(); it != value_->end(); ++it)
    out.emplace_back(it.key(), JsonNode(it.value(), childPath(pointer_, it.key())));
  return out;
}

eng::Result<size_t> JsonNode::size() const {
  if (!value_->is_array()) return typeError("an array");
  return value_->size();
}

JsonNode JsonNode::element(size_t index) const {
  assert(value_->is_array() && index < value_->size());
  return JsonNode((*value_)[index], childPath(pointer_, index));
}

eng::Result<float> JsonNode::number() const {
  if (!value_->is_number()) return typeError("a number");
  const double v = value_->get<double>();
  if (!std::isfinite(v) || std::abs(v) > 3.0e38) return error("number " + value_->dump() + " is not a finite float");
  return static_cast<float>(v);
}

eng::Result<bool> JsonNode::boolean() const {
  if (!value_->is_boolean()) return typeError("true or false");
  return value_->get<bool>();
}

eng::Result<std::string> JsonNode::string() const {
  if (!value_->is_string()) return typeError("a string");
  return value_->get<std::string>();
}

eng::Result<float> JsonNode::numberAt(std::string_view key) const { return ENG_TRY_VALUE(at(key)).number(); }

eng::Result<std::string> JsonNode::stringAt(std::string_view key) const { return ENG_TRY_VALUE(at(key)).string(); }

eng::Result<float> JsonNode::numberOr(std::string_view key, float fallback) const {
  auto v = find(key);
  return v ? v->number() : eng::Result<float>(fallback);
}

eng::Result<bool> JsonNode::booleanOr(std::string_view key, bool fallback) const {
  auto v = find(key);
  return v ? v->boolean() : eng::Result<bool>(fallback);
}

eng::Result<std::string> JsonNode::stringOr(std::string_view key, std::string fallback) const {
  auto v = find(key);
  return v ? v->string() : eng::Result<std::string>(std::move(fallback));
}

eng::Result<void> requireVersion(const JsonNode& document, int version) {
  if (!document.isObject()) return document.error("expected a JSON object at the top level");
  const JsonNode v = ENG_TRY_VALUE(document.at("version"));
  if (auto supported = checkFormatVersion(v.raw(), version); !supported) return v.error(supported.error());
  return {};
}

}  // namespace facial
