#include "bake/head/value_noise.h"

#include <cmath>

namespace bake {

float latticeHash(int32_t x, int32_t y, int32_t z, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B1u;
  h ^= static_cast<uint32_t>(x) * 0x85EBCA77u;
  h = (h << 13) | (h >> 19);
  h ^= static_cast<uint32_t>(y) * 0xC2B2AE3Du;
  h = (h << 17) | (h >> 15);
  h ^= static_cast<uint32_t>(z) * 0x27D4EB2Fu;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  h *= 0x297A2D39u;
  h ^= h >> 15;
  return static_cast<float>(h >> 8) / 16777216.0f;
}

float valueNoise(const glm::vec3& p, uint32_t seed) {
  const glm::vec3 f = glm::floor(p);
  const glm::vec3 t = p - f;
  const glm::vec3 s = t * t * (3.0f - 2.0f * t);
  const int32_t x = static_cast<int32_t>(f.x), y = static_cast<int32_t>(f.y), z = static_cast<int32_t>(f.z);
  auto h = [&](int dx, int dy, int dz) { return latticeHash(x + dx, y + dy, z + dz, seed); };
  const float x00 = h(0, 0, 0) + (h(1, 0, 0) - h(0, 0, 0)) * s.x;
  const float x10 = h(0, 1, 0) + (h(1, 1, 0) - h(0, 1, 0)) * s.x;
  const float x01 = h(0, 0, 1) + (h(1, 0, 1) - h(0, 0, 1)) * s.x;
  const float x11 = h(0, 1, 1) + (h(1, 1, 1) - h(0, 1, 1)) * s.x;
  const float y0 = x00 + (x10 - x00) * s.y;
  const float y1 = x01 + (x11 - x01) * s.y;
  return y0 + (y1 - y0) * s.z;
}

float fractalNoise(const glm::vec3& p, int octaves, uint32_t seed) {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
  glm::vec3 q = p;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * valueNoise(q, seed + static_cast<uint32_t>(i) * 101u);
    total += amplitude;
    amplitude *= 0.5f;
    q *= 2.0f;
  }
  return sum / total;
}

}  // namespace bake
