#include "engine/image/contact_sheet.h"

#include <gtest/gtest.h>

namespace {

eng::ContactSheetTile tile(int w, int h, uint8_t grey, std::string label) {
  return {eng::Canvas(w, h, {grey, grey, grey, 255}), std::move(label)};
}

TEST(ContactSheetValidity, RejectsEmptyInput) {
  auto sheet = eng::composeContactSheet({}, {});
  ASSERT_FALSE(sheet.ok());
  EXPECT_NE(sheet.error().message.find("no tiles"), std::string::npos);
}

TEST(ContactSheetValidity, RejectsTilesOfDifferentSizesNamingTheTile) {
  auto sheet = eng::composeContactSheet({tile(8, 8, 10, "a"), tile(8, 9, 10, "b")}, {});
  ASSERT_FALSE(sheet.ok());
  EXPECT_NE(sheet.error().message.find("tile 1 is 8x9, expected 8x8"), std::string::npos);
}

TEST(ContactSheetTest, LaysTilesOutInRowsWithLabels) {
  eng::ContactSheetOptions options;
  options.columns = 2;
  options.padding = 4;
  options.labelHeight = 12;
  auto sheet = eng::composeContactSheet({tile(20, 10, 200, "one"), tile(20, 10, 100, "two"), tile(20, 10, 50, "x")},
                                        options);
  ASSERT_TRUE(sheet.ok()) << sheet.error().message;
  const int labelBand = 18;
  EXPECT_EQ(sheet->width, 2 * (20 + 4) + 4);
  EXPECT_EQ(sheet->height, 2 * (10 + labelBand + 4) + 4);
  // Top-left pixel of the first and second tiles carry their colours.
  EXPECT_EQ(sheet->rgba[(4 * sheet->width + 4) * 4], 200);
  EXPECT_EQ(sheet->rgba[(4 * sheet->width + 4 + 24) * 4], 100);
  // The label band under the first tile has some bright (text) pixels.
  int bright = 0;
  for (int y = 14; y < 14 + labelBand; ++y)
    for (int x = 4; x < 24; ++x) bright += sheet->rgba[(y * sheet->width + x) * 4] > 150;
  EXPECT_GT(bright, 3);
}

}  // namespace
