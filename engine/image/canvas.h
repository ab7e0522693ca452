#pragma once
// An RGBA8 image in memory that tools draw into (contact sheets, overlays).
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

struct Canvas {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4, row 0 at the top

  Canvas() = default;
  Canvas(int w, int h, glm::u8vec4 fill = {0, 0, 0, 255});

  // Copies `src` (srcW x srcH RGBA8) with its top-left corner at (x, y), clipped.
  void blit(std::span<const uint8_t> src, int srcW, int srcH, int x, int y);
  void fillRect(int x, int y, int w, int h, glm::u8vec4 colour);
};

}  // namespace eng
