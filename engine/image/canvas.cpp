#include "engine/image/canvas.h"

#include <algorithm>
#include <cstring>

namespace eng {

Canvas::Canvas(int w, int h, glm::u8vec4 fill) : width(w), height(h), rgba(static_cast<size_t>(w) * h * 4) {
  fillRect(0, 0, w, h, fill);
}

void Canvas::blit(std::span<const uint8_t> src, int srcW, int srcH, int x, int y) {
  const int x0 = std::max(0, x), x1 = std::min(width, x + srcW);
  const int y0 = std::max(0, y), y1 = std::min(height, y + srcH);
  if (x0 >= x1 || y0 >= y1 || src.size() < static_cast<size_t>(srcW) * srcH * 4) return;
  for (int row = y0; row < y1; ++row) {
    const uint8_t* from = src.data() + (static_cast<size_t>(row - y) * srcW + (x0 - x)) * 4;
    std::memcpy(rgba.data() + (static_cast<size_t>(row) * width + x0) * 4, from, static_cast<size_t>(x1 - x0) * 4);
  }
}

void Canvas::fillRect(int x, int y, int w, int h, glm::u8vec4 colour) {
  const int x0 = std::max(0, x), x1 = std::min(width, x + w);
  const int y0 = std::max(0, y), y1 = std::min(height, y + h);
  for (int row = y0; row < y1; ++row)
    for (int col = x0; col < x1; ++col) {
      uint8_t* p = rgba.data() + (static_cast<size_t>(row) * width + col) * 4;
      p[0] = colour.r; p[1] = colour.g; p[2] = colour.b; p[3] = colour.a;
    }
}

}  // namespace eng
