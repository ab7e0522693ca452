#include "bake/head/teeth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>

#include "engine/core/uv_raster.h"

namespace bake {
namespace {

constexpr int kAlong = 84;  // columns along the arch
constexpr int kAround = 20;  // vertices around the cross-section
constexpr float kRoundness = 0.35f;  // superellipse exponent of the cross-section

// Tooth borders as fractions of the half arch (incisors, canine, premolars, molar).
constexpr std::array<float, 6> kBorders = {0.0f, 0.205f, 0.375f, 0.555f, 0.725f, 0.88f};

float signedPow(float v, float e) { return (v < 0 ? -1.0f : 1.0f) * std::pow(std::abs(v), e); }

// Distance (in half-arch fractions) from |s| to the nearest tooth border.
float borderDistance(float s) {
  float best = 1.0f;
  for (float b : kBorders) best = std::min(best, std::abs(std::abs(s) - b));
  return best;
}

}  // namespace

ToothRowShape upperToothRow(const glm::vec3& seam) {
  ToothRowShape r;
  r.upper = true;
  r.halfWidth = 0.0205f;
  r.frontZ = seam.z - 0.0072f;
  r.archDepth = 0.0115f;
  r.edgeY = seam.y - 0.0012f;
  r.rootY = seam.y + 0.0095f;
  r.thickness = 0.0056f;
  return r;
}

ToothRowShape lowerToothRow(const glm::vec3& seam) {
  ToothRowShape r;
  r.upper = false;
  r.halfWidth = 0.0178f;
  r.frontZ = seam.z - 0.0092f;
  r.archDepth = 0.0105f;
  r.edgeY = seam.y - 0.0004f;
  r.rootY = seam.y - 0.0080f;
  r.thickness = 0.0050f;
  return r;
}

PartMesh buildToothRow(const ToothRowShape& shape) {
  PartMesh m;
  const float rootSign = shape.upper ? 1.0f : -1.0f;
  auto position = [&](float s, float a) {
    const glm::vec3 arch(s * shape.halfWidth, 0.0f, shape.frontZ - shape.archDepth * s * s);
    const glm::vec3 tangent = glm::normalize(glm::vec3(shape.halfWidth, 0.0f, -2.0f * shape.archDepth * s));
    const glm::vec3 inward = glm::cross(glm::vec3(0, 1, 0), tangent);
    // Crowns get shorter toward the back; each tooth's edge corners are rounded off.
    const float height = std::abs(shape.rootY - shape.edgeY) * (1.0f - 0.3f * s * s);
    const float toward = signedPow(std::sin(a), kRoundness);  // +1 root side, -1 biting edge
    const float edgeWeight = std::pow(std::max(0.0f, -toward), 3.0f);
    const float scallop = 0.0007f * (1.0f - glm::smoothstep(0.0f, 0.035f, borderDistance(s))) * edgeWeight;
    const float h = (toward * 0.5f + 0.5f) * height + scallop;
    const float taper = 0.45f + 0.55f * (toward * 0.5f + 0.5f);  // thin biting edge
    const float depth = 0.5f * shape.thickness * taper * (1.0f - signedPow(std::cos(a), kRoundness));
    return arch + inward * depth + glm::vec3(0.0f, shape.edgeY + rootSign * h, 0.0f);
  };
  // Grid: column c along the arch, row k around the section (k = kAround repeats 0).
  std::vector<uint32_t> ids;
  for (int c = 0; c <= kAlong; ++c) {
    const float s = -1.0f + 2.0f * c / kAlong;
    uint32_t first = 0;
    for (int k = 0; k <= kAround; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * (k % kAround) / kAround;
      const uint32_t v = m.addVertex(position(s, a), glm::vec2(float(c) / kAlong, float(k) / kAround),
                                     k == kAround ? first : UINT32_MAX);
      if (k == 0) first = v;
      ids.push_back(v);
    }
  }
  auto at = [&](int c, int k) { return ids[size_t(c) * (kAround + 1) + k]; };
  // Winding flips for the upper row: its section runs up, the lower row's down.
  auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    if (shape.upper)
      m.indices.insert(m.indices.end(), {a, c, b, a, d, c});
    else
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
  };
  for (int c = 0; c < kAlong; ++c)
    for (int k = 0; k < kAround; ++k) quad(at(c, k), at(c, k + 1), at(c + 1, k + 1), at(c + 1, k));
  // End caps.
  for (int end = 0; end < 2; ++end) {
    const int c = end == 0 ? 0 : kAlong;
    glm::vec3 centre(0.0f);
    for (int k = 0; k < kAround; ++k) centre += m.positions[at(c, k)];
    centre /= float(kAround);
    const uint32_t mid = m.addVertex(centre, glm::vec2(float(c) / kAlong, 0.5f), UINT32_MAX);
    const glm::vec3 outward(end == 0 ? -1.0f : 1.0f, 0.0f, 0.0f);
    for (int k = 0; k < kAround; ++k) {
      uint32_t a = at(c, k), b = at(c, k + 1);
      const glm::vec3 n = glm::cross(m.positions[b] - centre, m.positions[a] - centre);
      if (glm::dot(n, outward) < 0.0f) std::swap(a, b);
      m.indices.insert(m.indices.end(), {mid, b, a});
    }
  }
  m.computeNormals();
  return m;
}

eng::Image paintTeethTexture(int width, int height) {
  eng::PaintImage img(width, height);
  // Ivory rather than paper white: bright teeth outshone the eyes at 256 px
  // and turned every open mouth into a white bar instead of an opening.
  const glm::vec3 enamel = eng::srgb(228, 220, 202), enamelRoot = eng::srgb(206, 192, 166);
  const glm::vec3 gap = eng::srgb(150, 138, 126), gum = eng::srgb(176, 88, 92);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float s = -1.0f + 2.0f * (x + 0.5f) / width;
      const float a = 2.0f * std::numbers::pi_v<float> * (y + 0.5f) / height;
      const float toward = signedPow(std::sin(a), kRoundness);
      const float front = std::cos(a);  // +1 front face, -1 inner face
      glm::vec3 c = glm::mix(enamel, enamelRoot, glm::smoothstep(-0.2f, 0.6f, toward));
      c = glm::mix(c, gap, 0.8f * (1.0f - glm::smoothstep(0.002f, 0.008f, borderDistance(s))));
      // Gum line, higher between the teeth.
      const float gumLine = 0.55f - 0.18f * (1.0f - glm::smoothstep(0.0f, 0.05f, borderDistance(s)));
      c = glm::mix(c, gum, glm::smoothstep(gumLine - 0.04f, gumLine + 0.04f, toward));
      c *= 0.55f + 0.45f * glm::smoothstep(-0.8f, 0.2f, front);  // the inner face sits in shadow
      c *= 1.0f - 0.6f * glm::smoothstep(0.45f, 1.0f, std::abs(s));  // back teeth in the dark
      img.set(x, y, glm::vec4(c, 1.0f));
    }
  eng::Image out;
  out.name = "teeth_base_color";
  out.width = width;
  out.height = height;
  out.rgba8 = img.toSrgba8();
  return out;
}

}  // namespace bake
