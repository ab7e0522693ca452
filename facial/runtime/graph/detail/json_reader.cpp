#include "facial/runtime/graph/detail/json_reader.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace facial::detail {

eng::Error jsonProblemError(const JsonProblem& problem, std::string_view source) {
  std::string message = source.empty() ? std::string() : std::string(source) + ": ";
  message += problem.pointer.empty() ? std::string_view("/") : std::string_view(problem.pointer);
  return eng::makeError(problem.kind, message + ": " + problem.problem);
}

void JsonNode::fail(const std::string& problem, eng::ErrorKind kind) const {
  throw JsonProblem{pointer_, problem, kind};
}

bool JsonNode::has(std::string_view key) const { return value_->is_object() && value_->contains(key); }

JsonNode JsonNode::at(std::string_view key) const {
  if (!value_->is_object()) fail("expected an object, got " + std::string(jsonTypeName(*value_)));
  auto it = value_->find(key);
  if (it == value_->end()) fail("missing \"" + std::string(key) + "\"");
  return JsonNode(*it, childPath(pointer_, key));
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

void JsonNode::allowOnly(std::initializer_list<std::string_view> known) const {
  if (!value_->is_object()) fail("expected an object, got " + std::string(jsonTypeName(*value_)));
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || k == it.key();
    if (ok) continue;
    std::string list;
    for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    JsonNode(*it, childPath(pointer_, it.key())).fail("unknown key (expected one of: " + list + ")");
  }
}

size_t JsonNode::size() const {
  if (!value_->is_array()) fail("expected an array, got " + std::string(jsonTypeName(*value_)));
  return value_->size();
}

JsonNode JsonNode::operator[](size_t index) const {
  if (index >= size()) fail("index " + std::to_string(index) + " out of range");
  return JsonNode((*value_)[index], childPath(pointer_, index));
}

float JsonNode::number() const {
  if (!value_->is_number()) fail("expected a number, got " + std::string(jsonTypeName(*value_)));
  const double v = value_->get<double>();
  if (!std::isfinite(v) || std::abs(v) > 3.0e38) fail("number " + value_->dump() + " is not a finite float");
  return static_cast<float>(v);
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + std::string(jsonTypeName(*value_)));
  return value_->get<bool>();
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("expected a string, got " + std::string(jsonTypeName(*value_)));
  return value_->get<std::string>();
}

float JsonNode::numberOr(std::string_view key, float fallback) const {
  auto v = find(key);
  return v ? v->number() : fallback;
}

bool JsonNode::booleanOr(std::string_view key, bool fallback) const {
  auto v = find(key);
  return v ? v->boolean() : fallback;
}

std::string JsonNode::stringOr(std::string_view key, std::string fallback) const {
  auto v = find(key);
  return v ? v->string() : std::move(fallback);
}

void requireVersion(const JsonNode& document, int version) {
  if (!document.isObject()) document.fail("expected a JSON object at the top level");
  const JsonNode v = document.at("version");
  if (auto supported = checkFormatVersion(v.raw(), version); !supported) v.fail(supported.error());
}

double jsonNumber(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text) - 1, value).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

}  // namespace facial::detail
