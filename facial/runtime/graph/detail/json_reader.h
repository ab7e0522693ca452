#pragma once
// Not installed (cmake/install.cmake leaves out every detail/ folder): the
// graph and timeline readers' machinery, shared by graph_json.cpp,
// timeline_json.cpp and curve_json.cpp.
//
// Typed reading of graph and timeline JSON on top of the rig layer's JSON
// plumbing (rig/json_document.h: file reading, pointers, error format).
// Readers throw JsonProblem, carrying the JSON pointer of the offending value
// ("/root/states/2/transitions/0/duration") and the problem, so a reader
// nested ten calls deep needs no error plumbing. Every public entry point
// (loadGraph, parseGraph, loadTimeline, timelineFromJson, keyframesFromJson,
// easingCurveFromJson) catches it once, at its edge, and returns it as an
// eng::Error through jsonProblemError(): no exception leaves the library.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/timeline.h"
#include "facial/runtime/json/json_document.h"

namespace facial::detail {

struct JsonProblem {
  std::string pointer;  // JSON pointer, "" for the document
  std::string problem;
  eng::ErrorKind kind = eng::ErrorKind::Malformed;  // kept from a nested load (a missing timeline file: NotFound)
};

// The one conversion at the edge: "<source>: <pointer>: <problem>" with the
// problem's kind (source "" leaves the source out: "<pointer>: <problem>").
eng::Error jsonProblemError(const JsonProblem& problem, std::string_view source);

class JsonNode {
 public:
  JsonNode(const Json& value, std::string pointer) : value_(&value), pointer_(std::move(pointer)) {}

  const Json& raw() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  [[noreturn]] void fail(const std::string& problem, eng::ErrorKind kind = eng::ErrorKind::Malformed) const;
  // An error from a layer that returns values (a nested file, a builder), at this node.
  [[noreturn]] void fail(const eng::Error& error) const { fail(error.message, error.kind); }

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

// The throwing readers of the shared forms (curve_json.h, timeline_json.h
// describe them); each fails naming the pointer of the offending value.
std::vector<Keyframe> parseKeyframes(const JsonNode& keys, KeyInterpolation defaultInterpolation);
KeyInterpolation parseKeyInterpolation(const JsonNode& name);
EasingCurve parseEasingCurve(const JsonNode& curve);
// A timeline object (without "version" when inline in a graph).
Timeline parseTimeline(const JsonNode& node, std::string defaultName);

}  // namespace facial::detail
