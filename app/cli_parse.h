#pragma once
// Option parsing shared by the subcommands.
#include <cstdint>
#include <string>
#include <string_view>

namespace app {

// "WxH" with 1..16384 pixels per side.
bool parseSize(const std::string& text, uint32_t& width, uint32_t& height);
// The whole text is one finite number.
bool parseFloat(std::string_view text, float& out);

}  // namespace app
