#pragma once
// Anti-aliased text labels drawn into a Canvas with stb_truetype (the copy
// Dear ImGui ships) and a system TrueType font (DejaVu Sans from Debian's
// fonts-dejavu-core).
#include <filesystem>
#include <memory>
#include <string_view>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/image/canvas.h"

namespace eng {

class TextRenderer {
 public:
  // Loads `fontFile`, or the default font when empty.
  static Result<TextRenderer> create(const std::filesystem::path& fontFile = {});
  TextRenderer(TextRenderer&&) noexcept;
  TextRenderer& operator=(TextRenderer&&) noexcept;
  ~TextRenderer();

  // Width in pixels of `text` at `pixelHeight`.
  int measure(std::string_view text, float pixelHeight) const;
  // Draws `text` with its top-left at (x, y).
  void draw(Canvas& canvas, std::string_view text, int x, int y, float pixelHeight, glm::u8vec4 colour) const;

  static std::filesystem::path defaultFontPath();

 private:
  struct Impl;
  explicit TextRenderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace eng
