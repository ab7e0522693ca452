#pragma once
// Typed reading of graph and timeline JSON on top of the rig layer's JSON
// plumbing (rig/json_document.h: file reading, pointers, error format).
// Readers throw JsonProblem, carrying the JSON pointer of the offending value
// ("/root/states/2/transitions/0/duration") and the problem; the public
// loaders catch it at their boundary and return it as an eng::Error through
// jsonError(), so callers only ever see errors as values.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "facial/runtime/rig/json_document.h"

namespace facial {

struct JsonProblem {
  std::string pointer;  // JSON pointer, "" for the document
  std::string problem;
};

class JsonNode {
 public:
  JsonNode(const Json& value, std::string pointer) : value_(&value), pointer_(std::move(pointer)) {}

  const Json& raw() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  [[noreturn]] void fail(const std::string& problem) const;

  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }
  bool isString() const { return value_->is_string(); }
  bool isNumber() const { return value_->is_number(); }

  // Object members. at() fails naming the missing key; find() returns nullopt.
  bool has(std::string_view key) const;
  JsonNode at(std::string_view key) const;
  std::optional<JsonNode> find(std::string_view key) const;
  // Fails on a member not in `known` (catches misspelt keys).
  void allowOnly(std::initializer_list<std::string_view> known) const;

  // Arrays.
  size_t size() const;  // fails unless an array
  JsonNode operator[](size_t index) const;

  // Scalars; each fails naming the expected type.
  float number() const;  // finite, in float range
  bool boolean() const;
  std::string string() const;
  float numberOr(std::string_view key, float fallback) const;
  bool booleanOr(std::string_view key, bool fallback) const;
  std::string stringOr(std::string_view key, std::string fallback) const;

 private:
  const Json* value_;
  std::string pointer_;
};

// Fails unless `document` is an object whose "version" equals `version`.
void requireVersion(const JsonNode& document, int version);

// The shortest decimal that reads back as `value` (0.1f is written 0.1, not 0.10000000149).
double jsonNumber(float value);

}  // namespace facial
