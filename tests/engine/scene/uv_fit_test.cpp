// UVs fitted into the unit square for a texture painted anew (engine/core/uv_raster.h).
#include <gtest/gtest.h>

#include "engine/core/uv_raster.h"

namespace {

TEST(FitIntoUnitSquare, UvsInsideAreKeptAndOthersTheirBoxOntoTheSquare) {
  std::vector<glm::vec2> inside = {{0.1f, 0.2f}, {0.9f, 0.5f}};
  eng::fitIntoUnitSquare(inside);
  EXPECT_EQ(inside[1], glm::vec2(0.9f, 0.5f));
  std::vector<glm::vec2> quantized = {{0.0f, 1024.0f}, {4095.0f, 4095.0f}, {2047.5f, 2559.5f}};
  eng::fitIntoUnitSquare(quantized);
  EXPECT_EQ(quantized[0], glm::vec2(0.0f, 0.0f));
  EXPECT_EQ(quantized[1], glm::vec2(1.0f, 1.0f));
  EXPECT_NEAR(quantized[2].x, 0.5f, 1e-6f);
  EXPECT_NEAR(quantized[2].y, 0.5f, 1e-6f);
}

// Two primitives that share one texture (facecap's skin with its lips a
// primitive of their own, UVs 0-4095) are fitted by their common box: the
// lips stay beside the rest instead of filling the whole texture over it.
TEST(FitIntoUnitSquare, PrimitivesSharingATextureKeepTheirPlacesInIt) {
  std::vector<glm::vec2> skin = {{0.0f, 0.0f}, {4095.0f, 4095.0f}};
  std::vector<glm::vec2> lips = {{1000.0f, 500.0f}, {2000.0f, 900.0f}};
  std::vector<glm::vec2>* both[] = {&skin, &lips};
  eng::fitIntoUnitSquare(both);
  EXPECT_EQ(skin[1], glm::vec2(1.0f));
  EXPECT_NEAR(lips[0].x, 1000.0f / 4095.0f, 1e-6f);
  EXPECT_NEAR(lips[1].y, 900.0f / 4095.0f, 1e-6f);
}

}  // namespace
