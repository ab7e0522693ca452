#pragma once
// Typed reading of a JSON document with errors as values: the one way the
// component reads its JSON (graphs, timelines, curves, the built-in head's
// rig spec). A JsonNode is a value plus its JSON pointer
// ("/root/states/2/transitions/0/duration"); every read that can fail returns
// an eng::Result whose message is "<pointer>: <problem>", and the entry point
// that knows the file puts it in front (error.prefixed("graph.json: ")).
// Readers of nested data chain the reads with ENG_TRY_VALUE (result.h):
//
//   eng::Result<Blend> readBlend(const JsonNode& j) {
//     ENG_TRY(j.allowOnly({"a", "b", "factor"}));
//     const float factor = ENG_TRY_VALUE(j.numberOr("factor", 0.5f));
//     return Blend{.a = ENG_TRY_VALUE(j.stringAt("a")), .factor = factor};  // not two reads in one aggregate: result.h
//   }
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/json/json_document.h"

namespace facial {

class JsonNode {
 public:
  JsonNode(const Json& value, std::string pointer) : value_(&value), pointer_(std::move(pointer)) {}

  const Json& raw() const { return *value_; }
  const std::string& pointer() const { return pointer_; }

  // "<pointer>: <problem>" ("/" for the document itself).
  eng::Error error(std::string_view problem, eng::ErrorKind kind = eng::ErrorKind::Malformed) const;
  // An error from a layer that returns values (a nested file, a builder), placed at this node; keeps its kind.
  eng::Error error(const eng::Error& cause) const { return error(cause.message, cause.kind); }

  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }
  bool isString() const { return value_->is_string(); }
  bool isNumber() const { return value_->is_number(); }

  // Object members. at() fails naming the missing key; find() is nullopt when
  // the key is absent (or this is not an object).
  bool has(std::string_view key) const;
  eng::Result<JsonNode> at(std::string_view key) const;
  std::optional<JsonNode> find(std::string_view key) const;
  // Fails on a member not in `known` (catches misspelt keys).
  eng::Result<void> allowOnly(std::initializer_list<std::string_view> known) const;
  // Every member in file order, for objects whose keys are data (names of
  // expressions, channels); fails unless this is an object. The keys point
  // into the document.
  eng::Result<std::vector<std::pair<std::string_view, JsonNode>>> members() const;

  // Arrays: size() fails unless this is an array; element(i) needs i < size().
  eng::Result<size_t> size() const;
  JsonNode element(size_t index) const;

  // Scalars; each fails naming the expected type.
  eng::Result<float> number() const;  // finite, in float range
  eng::Result<bool> boolean() const;
  eng::Result<std::string> string() const;
  // Members: required (at + the scalar) or with a fallback when absent.
  eng::Result<float> numberAt(std::string_view key) const;
  eng::Result<std::string> stringAt(std::string_view key) const;
  eng::Result<float> numberOr(std::string_view key, float fallback) const;
  eng::Result<bool> booleanOr(std::string_view key, bool fallback) const;
  eng::Result<std::string> stringOr(std::string_view key, std::string fallback) const;

 private:
  eng::Error typeError(std::string_view expected) const;

  const Json* value_;
  std::string pointer_;
};

// Fails unless `document` is an object whose "version" the reader supports
// (checkFormatVersion: a newer file is refused with its version and ours).
eng::Result<void> requireVersion(const JsonNode& document, int version);

}  // namespace facial
