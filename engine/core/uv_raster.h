#pragma once
// Texture painting support: walks every texel centre covered by a mesh's
// triangles in UV space, so a painter can evaluate colour from interpolated
// surface attributes (rest position, region facts), then grows painted texels
// into the empty gutter so bilinear filtering and mipmaps do not bleed black.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

// Calls `texel(x, y, triangle, barycentric)` once per covered texel centre
// (texture y down, uv.y = 0 at the top row, as in glTF). The first triangle
// to cover a texel wins.
void rasterizeUv(int width, int height, std::span<const glm::vec2> uvs, std::span<const uint32_t> indices,
                 const std::function<void(int x, int y, uint32_t triangle, const glm::vec3& barycentric)>& texel);

// Image under construction: linear-light RGBA floats plus a coverage flag.
struct PaintImage {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;
  std::vector<uint8_t> covered;

  PaintImage(int w, int h, const glm::vec4& fill = glm::vec4(0.0f))
      : width(w), height(h), texels(size_t(w) * h, fill), covered(size_t(w) * h, 0) {}
  void set(int x, int y, const glm::vec4& c) {
    texels[size_t(y) * width + x] = c;
    covered[size_t(y) * width + x] = 1;
  }
  // Copies covered texels into uncovered neighbours, `passes` texels deep.
  void dilate(int passes);
  // RGBA8: rgb linear -> sRGB, alpha kept linear.
  std::vector<uint8_t> toSrgba8() const;
};

// UVs outside [0, 1] moved and scaled into it (their box onto the unit
// square), for a texture painted anew that replaces whatever they were made
// for: a face whose texture was dropped (KTX2) can keep quantized UVs that
// only its texture transform mapped into [0, 1]. UVs inside are kept.
void fitIntoUnitSquare(std::vector<glm::vec2>& uvs);
// The same for the UV sets of several primitives that share one texture (a
// material's): their common box onto the unit square, so they stay apart
// as they were instead of each filling the whole texture.
void fitIntoUnitSquare(std::span<std::vector<glm::vec2>* const> uvSets);

float srgbToLinear(float c);
float linearToSrgb(float c);
glm::vec3 srgb(int r, int g, int b);  // 8-bit sRGB triple -> linear colour

}  // namespace eng
