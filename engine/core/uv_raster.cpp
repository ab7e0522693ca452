#include "engine/core/uv_raster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace eng {

void rasterizeUv(int width, int height, std::span<const glm::vec2> uvs, std::span<const uint32_t> indices,
                 const std::function<void(int, int, uint32_t, const glm::vec3&)>& texel) {
  std::vector<uint8_t> done(size_t(width) * height, 0);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    glm::vec2 p[3];
    for (int k = 0; k < 3; ++k) p[k] = uvs[indices[t + k]] * glm::vec2(width, height);
    const float area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    if (std::abs(area) < 1e-12f) continue;
    const int x0 = std::max(0, int(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
    const int x1 = std::min(width - 1, int(std::ceil(std::max({p[0].x, p[1].x, p[2].x}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
    const int y1 = std::min(height - 1, int(std::ceil(std::max({p[0].y, p[1].y, p[2].y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        if (done[size_t(y) * width + x]) continue;
        const glm::vec2 c(x + 0.5f, y + 0.5f);
        const float b0 = ((p[1].x - c.x) * (p[2].y - c.y) - (p[2].x - c.x) * (p[1].y - c.y)) / area;
        const float b1 = ((p[2].x - c.x) * (p[0].y - c.y) - (p[0].x - c.x) * (p[2].y - c.y)) / area;
        const float b2 = 1.0f - b0 - b1;
        const float eps = -1e-5f;
        if (b0 < eps || b1 < eps || b2 < eps) continue;
        done[size_t(y) * width + x] = 1;
        texel(x, y, static_cast<uint32_t>(t / 3), glm::vec3(b0, b1, b2));
      }
  }
}

void fitIntoUnitSquare(std::vector<glm::vec2>& uvs) {
  std::vector<glm::vec2>* one = &uvs;
  fitIntoUnitSquare(std::span<std::vector<glm::vec2>* const>(&one, 1));
}

void fitIntoUnitSquare(std::span<std::vector<glm::vec2>* const> uvSets) {
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const std::vector<glm::vec2>* uvs : uvSets)
    for (const glm::vec2& uv : *uvs) lo = glm::min(lo, uv), hi = glm::max(hi, uv);
  if (lo.x >= 0.0f && lo.y >= 0.0f && hi.x <= 1.0f && hi.y <= 1.0f) return;
  const glm::vec2 size = glm::max(hi - lo, glm::vec2(1e-12f));
  for (std::vector<glm::vec2>* uvs : uvSets)
    for (glm::vec2& uv : *uvs) uv = (uv - lo) / size;
}

void PaintImage::dilate(int passes) {
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<uint8_t> next = covered;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = size_t(y) * width + x;
        if (covered[i]) continue;
        glm::vec4 sum(0.0f);
        int count = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const size_t j = size_t(ny) * width + nx;
            if (covered[j]) {
              sum += texels[j];
              ++count;
            }
          }
        if (count) {
          texels[i] = sum / float(count);
          next[i] = 1;
        }
      }
    covered.swap(next);
  }
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}
glm::vec3 srgb(int r, int g, int b) {
  // Painters call this per texel: decode the 256 possible values once.
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(i / 255.0f);
    return t;
  }();
  auto at = [](int v) { return table[size_t(std::clamp(v, 0, 255))]; };
  return glm::vec3(at(r), at(g), at(b));
}

std::vector<uint8_t> PaintImage::toSrgba8() const {
  std::vector<uint8_t> out(texels.size() * 4);
  for (size_t i = 0; i < texels.size(); ++i) {
    const glm::vec4& c = texels[i];
    // Runs of one value (the background an image was made with) are encoded once.
    if (i > 0 && c == texels[i - 1]) {
      std::copy_n(&out[(i - 1) * 4], 4, &out[i * 4]);
      continue;
    }
    out[i * 4 + 0] = static_cast<uint8_t>(std::lround(linearToSrgb(c.r) * 255.0f));
    out[i * 4 + 1] = static_cast<uint8_t>(std::lround(linearToSrgb(c.g) * 255.0f));
    out[i * 4 + 2] = static_cast<uint8_t>(std::lround(linearToSrgb(c.b) * 255.0f));
    out[i * 4 + 3] = static_cast<uint8_t>(std::lround(std::clamp(c.a, 0.0f, 1.0f) * 255.0f));
  }
  return out;
}

}  // namespace eng
