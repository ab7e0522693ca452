#include "engine/image/canvas.h"

#include <gtest/gtest.h>

namespace {

TEST(CanvasTest, BlitCopiesPixelsAtOffset) {
  eng::Canvas canvas(4, 3, {0, 0, 0, 255});
  const std::vector<uint8_t> red = {255, 0, 0, 255, 255, 0, 0, 255};  // 2x1
  canvas.blit(red, 2, 1, 1, 2);
  EXPECT_EQ(canvas.rgba[(2 * 4 + 1) * 4], 255);
  EXPECT_EQ(canvas.rgba[(2 * 4 + 2) * 4], 255);
  EXPECT_EQ(canvas.rgba[(2 * 4 + 0) * 4], 0);
  EXPECT_EQ(canvas.rgba[(1 * 4 + 1) * 4], 0);
}

TEST(CanvasTest, BlitClipsOutsideTheCanvas) {
  eng::Canvas canvas(2, 2, {0, 0, 0, 255});
  const std::vector<uint8_t> white(3 * 3 * 4, 255);
  canvas.blit(white, 3, 3, 1, 1);  // only pixel (1,1) lands inside
  EXPECT_EQ(canvas.rgba[(1 * 2 + 1) * 4], 255);
  EXPECT_EQ(canvas.rgba[0], 0);
  canvas.blit(white, 3, 3, -5, -5);  // entirely outside: nothing changes, no crash
  EXPECT_EQ(canvas.rgba[0], 0);
}

TEST(CanvasTest, FillRectClips) {
  eng::Canvas canvas(3, 3, {0, 0, 0, 255});
  canvas.fillRect(-1, -1, 2, 2, {9, 8, 7, 255});
  EXPECT_EQ(canvas.rgba[0], 9);
  EXPECT_EQ(canvas.rgba[4], 0);
}

}  // namespace
