#include "facial/runtime/graph/detail/json_reader.h"

#include <charconv>
#include <cstdlib>

namespace facial::detail {

double jsonNumber(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text) - 1, value).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

}  // namespace facial::detail
