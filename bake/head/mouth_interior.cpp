#include "bake/head/mouth_interior.h"

#include <algorithm>

#include "engine/core/uv_raster.h"

namespace bake {

eng::Image paintMouthInteriorTexture(int height) {
  const int width = 4;
  eng::PaintImage img(width, height);
  const glm::vec3 innerLip = eng::srgb(178, 86, 86), gums = eng::srgb(118, 46, 48), back = eng::srgb(40, 13, 15),
                  throat = eng::srgb(16, 5, 6);
  for (int y = 0; y < height; ++y) {
    const float v = (y + 0.5f) / height;
    glm::vec3 c;
    if (v < 0.15f)
      c = glm::mix(innerLip, gums, v / 0.15f);
    else if (v < 0.45f)
      c = glm::mix(gums, back, (v - 0.15f) / 0.30f);
    else
      c = glm::mix(back, throat, std::min(1.0f, (v - 0.45f) / 0.45f));
    for (int x = 0; x < width; ++x) img.set(x, y, glm::vec4(c, 1.0f));
  }
  eng::Image out;
  out.name = "mouth_interior_base_color";
  out.width = width;
  out.height = height;
  out.rgba8 = img.toSrgba8();
  return out;
}

}  // namespace bake
