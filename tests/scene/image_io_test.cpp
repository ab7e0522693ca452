// PNG writing and image reading through stb.
#include <gtest/gtest.h>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/scene/gltf_test_files.h"

namespace {

using testing_support::freshTempDir;

std::vector<uint8_t> gradient(int w, int h) {
  std::vector<uint8_t> rgba;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      rgba.push_back(static_cast<uint8_t>(255 * x / (w - 1)));
      rgba.push_back(static_cast<uint8_t>(255 * y / (h - 1)));
      rgba.push_back(128);
      rgba.push_back(255);
    }
  return rgba;
}

TEST(ImageIo, PngWriteReadRoundTripIsLossless) {
  const auto dir = freshTempDir("image_io_roundtrip");
  const std::vector<uint8_t> pixels = gradient(64, 32);
  ASSERT_TRUE(eng::writePng(dir / "gradient.png", 64, 32, pixels).ok());
  auto img = eng::readImage(dir / "gradient.png");
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->width, 64);
  EXPECT_EQ(img->height, 32);
  EXPECT_EQ(img->rgba8, pixels);
  EXPECT_EQ(img->name, (dir / "gradient.png").string());
}

TEST(ImageIo, EncodeDecodeInMemory) {
  const std::vector<uint8_t> pixels = gradient(3, 2);
  auto png = eng::encodePng(3, 2, pixels);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ((*png)[1], 'P');
  auto img = eng::decodeImage(*png, "mem");
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->rgba8, pixels);
}

TEST(ImageIoBadInput, SizeMismatchMissingFileAndCorruptData) {
  const auto dir = freshTempDir("image_io_bad");
  auto written = eng::writePng(dir / "x.png", 4, 4, std::vector<uint8_t>(10));
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find("needs 64 RGBA8 bytes, got 10"), std::string::npos) << written.error().message;
  auto missing = eng::readImage(dir / "missing.png");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("missing.png: file not found"), std::string::npos);
  scene_test::writeBytes(dir / "junk.png", {0x89, 'P', 'N', 'G', 0, 1, 2});
  auto junk = eng::readImage(dir / "junk.png");
  ASSERT_FALSE(junk.ok());
  EXPECT_NE(junk.error().message.find("not a decodable image"), std::string::npos) << junk.error().message;
}

TEST(ImageIoBadInput, ForgedHugeDimensionsAreRefusedBeforeDecoding) {
  auto png = eng::encodePng(1, 1, std::vector<uint8_t>{1, 2, 3, 4});
  ASSERT_TRUE(png.ok());
  std::vector<uint8_t> forged = *png;
  // IHDR width and height (big-endian) start at byte 16: claim 10000 x 10000,
  // which stb would accept and allocate 400 MB for.
  const uint8_t big[4] = {0x00, 0x00, 0x27, 0x10};
  std::copy(big, big + 4, forged.begin() + 16);
  std::copy(big, big + 4, forged.begin() + 20);
  auto img = eng::decodeImage(forged, "forged.png");
  ASSERT_FALSE(img.ok());
  EXPECT_EQ(img.error().message,
            "forged.png: image too large: 10000x10000, the limit is 16384 per side and 67108864 pixels");
}

// stb refuses to even read the header of what it could not decode; the refusal must still say why.
TEST(ImageIoBadInput, HeaderBeyondWhatStbAcceptsIsRefusedAsTooLarge) {
  auto png = eng::encodePng(1, 1, std::vector<uint8_t>{1, 2, 3, 4});
  ASSERT_TRUE(png.ok());
  std::vector<uint8_t> forged = *png;
  const uint8_t side[4] = {0x00, 0x00, 0xEA, 0x60};  // 60000
  std::copy(side, side + 4, forged.begin() + 16);
  std::copy(side, side + 4, forged.begin() + 20);
  auto img = eng::decodeImage(forged, "huge.png");
  ASSERT_FALSE(img.ok());
  EXPECT_EQ(img.error().message, "huge.png: image too large: 60000x60000, the limit is 16384 per side and 67108864 pixels");
  // One side past the limit, the area under it.
  const uint8_t wide[4] = {0x00, 0x00, 0x4E, 0x20}, low[4] = {0x00, 0x00, 0x00, 0x10};  // 20000 x 16
  std::copy(wide, wide + 4, forged.begin() + 16);
  std::copy(low, low + 4, forged.begin() + 20);
  img = eng::decodeImage(forged, "wide.png");
  ASSERT_FALSE(img.ok());
  EXPECT_NE(img.error().message.find("wide.png: image too large: 20000x16"), std::string::npos) << img.error().message;
  // A JPEG frame header (SOI, SOF0 with height 60000, width 50000), nothing after it.
  const std::vector<uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x04, 0x00, 0x00, 0xFF, 0xC0, 0x00, 0x11,
                                     0x08, 0xEA, 0x60, 0xC3, 0x50, 0x03, 0x01, 0x11, 0x00};
  img = eng::decodeImage(jpeg, "huge.jpg");
  ASSERT_FALSE(img.ok());
  EXPECT_NE(img.error().message.find("huge.jpg: image too large: 50000x60000"), std::string::npos) << img.error().message;
}

}  // namespace
