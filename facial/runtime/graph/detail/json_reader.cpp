#include "facial/runtime/graph/detail/json_reader.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace facial::detail {

namespace {

// A container being walked by checkNumberRange and the child it is at.
struct Frame {
  const Json* container;
  Json::const_iterator child;
  size_t index;  // of `child`, for arrays
};

std::string escapedPointerToken(std::string_view key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// The JSON pointer of the innermost frame's child, below `base` (the root's pointer).
std::string pointerOf(const std::vector<Frame>& stack, const std::string& base) {
  std::string out = base;
  for (const Frame& f : stack)
    out += "/" + (f.container->is_object() ? escapedPointerToken(f.child.key()) : std::to_string(f.index));
  return out;
}

bool outOfRange(const Json& value) { return value.is_number() && !(std::abs(value.get<double>()) <= kMaxFileNumber); }

eng::Error rangeError(const Json& value, std::string pointer) {
  return JsonNode(value, std::move(pointer))
      .error("number " + value.dump() + " is outside [-1e+06, 1e+06], the range a graph, timeline or curve may hold");
}

}  // namespace

double jsonNumber(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text) - 1, value).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

eng::Result<void> checkNumberRange(const JsonNode& root) {
  if (outOfRange(root.raw())) return rangeError(root.raw(), root.pointer());
  std::vector<Frame> stack;  // as deep as the document nests, never as long as it is
  if (root.raw().is_structured()) stack.push_back({&root.raw(), root.raw().begin(), 0});
  while (!stack.empty()) {
    Frame& top = stack.back();
    if (top.child == top.container->end()) {
      stack.pop_back();
      if (!stack.empty()) ++stack.back().child, ++stack.back().index;
      continue;
    }
    const Json& value = *top.child;
    if (outOfRange(value)) return rangeError(value, pointerOf(stack, root.pointer()));
    if (value.is_structured()) {
      stack.push_back({&value, value.begin(), 0});
    } else {
      ++top.child;
      ++top.index;
    }
  }
  return {};
}

}  // namespace facial::detail
