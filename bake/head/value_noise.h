#pragma once
// Deterministic value noise for procedural textures (integer hashing only, so
// every build paints the same texels).
#include <cstdint>

#include <glm/glm.hpp>

namespace bake {

// Hash of integer lattice coordinates to [0, 1).
float latticeHash(int32_t x, int32_t y, int32_t z, uint32_t seed);
// Smooth value noise in [0, 1) with unit lattice spacing.
float valueNoise(const glm::vec3& p, uint32_t seed);
// Sum of `octaves` noise layers, each at twice the frequency and half the
// amplitude of the last, normalised to [0, 1).
float fractalNoise(const glm::vec3& p, int octaves, uint32_t seed);

}  // namespace bake
