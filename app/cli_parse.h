#pragma once
// Option parsing shared by the subcommands.
#include <cstdint>
#include <string>
#include <string_view>

namespace app {

// "WxH" with 1..16384 pixels per side.
bool parseSize(const std::string& text, uint32_t& width, uint32_t& height);

}  // namespace app
