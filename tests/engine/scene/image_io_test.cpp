// PNG writing (libpng) and image reading (stb).
#include <string>

#include <gtest/gtest.h>
#include <zlib.h>

#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using testing_support::freshTempDir;

void appendChunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data) {
  const auto be32 = [&](uint32_t v) { for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<uint8_t>(v >> s)); };
  be32(static_cast<uint32_t>(data.size()));
  const size_t typeAt = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  be32(static_cast<uint32_t>(crc32(0, png.data() + typeAt, static_cast<uInt>(png.size() - typeAt))));
}

// A PNG whose image data is `raw` (filtered scanlines) deflated as it stands, whatever the
// header says it should hold.
std::vector<uint8_t> handMadePng(uint32_t w, uint32_t h, uint8_t colourType, bool interlaced, const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<uint8_t> header;
  for (uint32_t v : {w, h})
    for (int s = 24; s >= 0; s -= 8) header.push_back(static_cast<uint8_t>(v >> s));
  header.insert(header.end(), {8, colourType, 0, 0, static_cast<uint8_t>(interlaced ? 1 : 0)});
  appendChunk(png, "IHDR", header);
  std::vector<uint8_t> deflated(compressBound(static_cast<uLong>(raw.size())));
  uLongf deflatedSize = static_cast<uLongf>(deflated.size());
  EXPECT_EQ(compress2(deflated.data(), &deflatedSize, raw.data(), static_cast<uLong>(raw.size()), 9), Z_OK);
  deflated.resize(deflatedSize);
  appendChunk(png, "IDAT", deflated);
  appendChunk(png, "IEND", {});
  return png;
}

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

// Noise (every byte, alpha too) does not compress: the encoder's output
// outgrows what it reserved, and each channel must still come back exactly.
TEST(ImageIo, IncompressibleNoiseWithAlphaRoundTripsExactly) {
  std::vector<uint8_t> pixels(size_t{97} * 61 * 4);
  uint32_t state = 12345;
  for (uint8_t& byte : pixels) {
    state = state * 1664525u + 1013904223u;
    byte = static_cast<uint8_t>(state >> 24);
  }
  auto png = eng::encodePng(97, 61, pixels);
  ASSERT_TRUE(png.ok()) << png.error().message;
  EXPECT_GT(png->size(), pixels.size() / 2);
  auto img = eng::decodeImage(*png, "noise");
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->width, 97);
  EXPECT_EQ(img->height, 61);
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

namespace {

// Validity: stb trusts a chunk's declared length and reallocates for it before reading;
// an IDAT that claims a gigabyte the file does not hold is refused by name first.
TEST(ImageIoBadInput, PngChunkLongerThanTheFileIsRefusedBeforeDecoding) {
  std::vector<uint8_t> png = handMadePng(1, 1, 6, false, {0, 1, 2, 3, 4});
  png.resize(png.size() - 12);  // IEND off
  const size_t at = png.size();
  png.insert(png.end(), {0x40, 0x00, 0x00, 0x01, 'I', 'D', 'A', 'T', 0, 0, 0, 0, 0, 0, 0, 0});
  auto img = eng::decodeImage(png, "long.png");
  ASSERT_FALSE(img.ok());
  EXPECT_EQ(img.error().message, "long.png: PNG chunk 'IDAT' at byte " + std::to_string(at) +
                                     " declares 1073741825 bytes, only 8 follow its header (truncated or corrupt file)");
}

// Validity: 64 MiB of zeros deflate to 64 kB; stb inflates all of it for a 1x1 image and
// decodes the first pixel. Refused before it inflates past twice what the header needs.
TEST(ImageIoBadInput, PngDataInflatingFarPastItsHeaderIsRefused) {
  auto img = eng::decodeImage(handMadePng(1, 1, 6, false, std::vector<uint8_t>(size_t{64} << 20)), "bomb.png");
  ASSERT_FALSE(img.ok());
  EXPECT_EQ(img.error().message,
            "bomb.png: PNG image data inflates past 4106 bytes, its header needs 5 (a decompression bomb or corrupt data)");
}

// Result: image data of exactly the size the header asks for decodes, interlaced (the seven
// Adam7 passes of a 5x3 grey image hold 2, 2, 0, 2, 4, 2x3 and 6 bytes, filter bytes included) or not.
TEST(ImageIo, HandMadePngStreamsOfTheExactSizeDecode) {
  const std::vector<uint8_t> interlaced = {0, 10, 0, 11, 0, 12, 0, 20, 21, 22, 0, 30, 31, 0, 32, 33, 0, 40, 41, 42, 43, 44};
  auto img = eng::decodeImage(handMadePng(5, 3, 0, true, interlaced), "adam7.png");
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->width, 5);
  EXPECT_EQ(img->height, 3);
  EXPECT_EQ(img->rgba8[0], 10);
  std::vector<uint8_t> rows;
  for (int y = 0; y < 3; ++y) rows.insert(rows.end(), {0, 1, 2, 3, 4, 5});
  img = eng::decodeImage(handMadePng(5, 3, 0, false, rows), "rows.png");
  ASSERT_TRUE(img.ok()) << img.error().message;
  EXPECT_EQ(img->rgba8[4 * 4], 5);
}

}  // namespace
