#pragma once
// A labelled grid of equally sized tiles (e.g. one render per emotion).
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "engine/image/canvas.h"

namespace eng {

struct ContactSheetTile {
  Canvas image;
  std::string label;
};

struct ContactSheetOptions {
  int columns = 4;
  int padding = 12;
  float labelHeight = 28.0f;  // label text size in pixels
  std::string title;          // optional heading across the top
  glm::u8vec4 background{34, 36, 40, 255};
  glm::u8vec4 labelColour{235, 235, 235, 255};
};

// All tiles must share one size; the message names the first tile that differs.
Result<Canvas> composeContactSheet(const std::vector<ContactSheetTile>& tiles, const ContactSheetOptions& options);

}  // namespace eng
