#pragma once
// A decoded texture read at UVs: bilinear, repeating; rgb decoded from sRGB,
// alpha as stored. For the face's own colour (autorig/brow_band) and the
// head's painted layers (autorig/detail_transfer).
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/core/uv_raster.h"
#include "engine/scene/model.h"

namespace autorig {

// Whether `image` holds its pixels (an undecodable one is kept empty).
inline bool decoded(const eng::Image& image) {
  return image.width > 0 && image.height > 0 && image.rgba8.size() == size_t(image.width) * size_t(image.height) * 4;
}

class Sampler {
 public:
  explicit Sampler(const eng::Image& image) : image_(image) {}
  glm::vec4 operator()(glm::vec2 uv) const {
    uv -= glm::floor(uv);
    const float x = uv.x * float(image_.width) - 0.5f, y = uv.y * float(image_.height) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float fx = x - float(x0), fy = y - float(y0);
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx),
                    fy);
  }

 private:
  glm::vec4 texel(int x, int y) const {
    x = ((x % image_.width) + image_.width) % image_.width;
    y = ((y % image_.height) + image_.height) % image_.height;
    const uint8_t* t = &image_.rgba8[(size_t(y) * size_t(image_.width) + size_t(x)) * 4];
    return {eng::srgb(t[0], t[1], t[2]), float(t[3]) / 255.0f};
  }
  const eng::Image& image_;
};

}  // namespace autorig
