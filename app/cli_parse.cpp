#include "app/cli_parse.h"

#include <charconv>
#include <string_view>

namespace app {

bool parseSize(const std::string& text, uint32_t& width, uint32_t& height) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return false;
  auto parse = [](std::string_view s, uint32_t& v) {
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && ptr == s.data() + s.size() && v > 0 && v <= 16384;
  };
  return parse(std::string_view(text).substr(0, x), width) && parse(std::string_view(text).substr(x + 1), height);
}

}  // namespace app
