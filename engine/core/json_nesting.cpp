#include "engine/core/json_nesting.h"

#include <algorithm>
#include <string>

namespace eng {

size_t jsonNestingDepth(std::string_view text) {
  size_t depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

Result<void> checkJsonNesting(std::string_view text, std::string_view source, size_t limit) {
  const size_t depth = jsonNestingDepth(text);
  if (depth <= limit) return {};
  return makeError(ErrorKind::TooLarge, std::string(source) + ": JSON nests " + std::to_string(depth) + " levels deep, more than the " +
                   std::to_string(limit) + " accepted");
}

}  // namespace eng
