#include "bake/head/eyeball.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>

#include "engine/core/uv_raster.h"
#include "bake/head/value_noise.h"

namespace bake {
namespace {


// Corneal bulge as a fraction of the radius, by angle from the gaze axis.
// Kept below the 0.4 mm the lid margins tuck into the ball, so lids sliding
// over the cornea never cut through it.
float bulge(float angleDegrees, float irisAngle) { return 0.017f * (1.0f - glm::smoothstep(0.0f, irisAngle + 4.0f, angleDegrees)); }

}  // namespace

PartMesh buildEyeball(const EyeOpening& eye, const HeadProportions& p) {
  const glm::vec3 centre = eye.centre();
  const float r = eye.radius();
  const float iris = p.irisAngle;
  return sphereGrid(32, 56, [&](const glm::vec3& d) {
    const float angle = std::acos(std::clamp(d.z, -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>;
    return centre + d * (r * (1.0f + bulge(angle, iris)));
  });
}

eng::Image paintEyeTexture(const HeadProportions& p, int width, int height) {
  eng::PaintImage img(width, height);
  // Sclera a little off-white: a pure white ball glared out of the face and
  // made every open eye look startled.
  const glm::vec3 sclera = eng::srgb(236, 231, 224), scleraShade = eng::srgb(214, 196, 190);
  // Hazel-brown: the commonest iris, and dark enough that the eyes keep
  // their weight at 256 px and in grey (a light blue iris read as skin-grey
  // there, and the face lost the two dark spots people look for first).
  const glm::vec3 irisInner = eng::srgb(128, 92, 48), irisMid = eng::srgb(86, 56, 30), irisOuter = eng::srgb(46, 30, 17);
  const glm::vec3 limbus = eng::srgb(24, 16, 12), pupil = eng::srgb(6, 6, 8);
  const glm::vec3 highlightDir = glm::normalize(glm::vec3(-0.32f, 0.42f, 1.0f));
  const glm::vec3 secondDir = glm::normalize(glm::vec3(0.26f, -0.30f, 1.0f));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float theta = std::numbers::pi_v<float> * (y + 0.5f) / height, phi = 2.0f * std::numbers::pi_v<float> * (x + 0.5f) / width;
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const float angle = theta * 180.0f / std::numbers::pi_v<float>;
      // Sclera, a little warmer and darker away from the front.
      glm::vec3 c = glm::mix(sclera, scleraShade, glm::smoothstep(45.0f, 95.0f, angle));
      // Iris: radial fibres over an inner-to-outer colour ramp.
      const float f = std::clamp((angle - p.pupilAngle) / (p.irisAngle - p.pupilAngle), 0.0f, 1.0f);
      glm::vec3 iris = f < 0.35f ? glm::mix(irisInner, irisMid, f / 0.35f) : glm::mix(irisMid, irisOuter, (f - 0.35f) / 0.65f);
      const float fibres = fractalNoise(glm::vec3(phi * 9.0f, angle * 0.35f, 0.0f), 3, 11u);
      iris *= 0.78f + 0.45f * fibres;
      iris = glm::mix(iris, limbus, glm::smoothstep(p.irisAngle - 4.0f, p.irisAngle - 0.5f, angle));
      const float irisCover = 1.0f - glm::smoothstep(p.irisAngle - 0.3f, p.irisAngle + 1.2f, angle);
      c = glm::mix(c, iris, irisCover);
      c = glm::mix(c, pupil, 1.0f - glm::smoothstep(p.pupilAngle - 0.6f, p.pupilAngle + 0.6f, angle));
      // The hidden back of the ball matches the pupil: a repeating sampler
      // blends the first and last rows at the poles.
      c = glm::mix(c, pupil, glm::smoothstep(150.0f, 165.0f, angle));
      // The upper lid and lashes shade the top of the ball: the opening reads
      // as a recess under the brow instead of a white almond pasted on the
      // skin. Painted, the shade turns with the ball when the eye looks
      // around; a gaze is a few degrees most of the time (saccades, the viewer)
      // and the lids follow a real eye's vertical turns much the same way.
      const float elevation = std::asin(std::clamp(d.y, -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>;
      c *= 1.0f - 0.38f * glm::smoothstep(-4.0f, p.upperLidHeight - 2.0f, elevation);
      // Corneal catch-lights, painted so that they read at 256 px on every
      // quality tier (they turn with the eye, like the shade above).
      const float h1 = std::acos(std::clamp(glm::dot(d, highlightDir), -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>;
      const float h2 = std::acos(std::clamp(glm::dot(d, secondDir), -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>;
      c = glm::mix(c, glm::vec3(1.0f), 1.0f - glm::smoothstep(4.0f, 5.5f, h1));
      c = glm::mix(c, glm::vec3(0.85f), 0.7f * (1.0f - glm::smoothstep(1.8f, 2.8f, h2)));
      img.set(x, y, glm::vec4(c, 1.0f));
    }
  eng::Image out;
  out.name = "eye_base_color";
  out.width = width;
  out.height = height;
  out.rgba8 = img.toSrgba8();
  return out;
}

}  // namespace bake
