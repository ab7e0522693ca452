#include "app/gif_writer.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "tests/common/test_support.h"

namespace {

TEST(GifWriterValidity, RejectsBadSizeAndRate) {
  auto dir = testing_support::freshTempDir("gif_validity");
  EXPECT_FALSE(app::GifWriter::create(dir / "a.gif", 0, 10, 30).ok());
  EXPECT_FALSE(app::GifWriter::create(dir / "a.gif", 10, 10, 0).ok());
}

TEST(GifWriterValidity, RejectsFrameOfWrongSize) {
  auto dir = testing_support::freshTempDir("gif_frame_size");
  auto gif = app::GifWriter::create(dir / "a.gif", 4, 4, 10);
  ASSERT_TRUE(gif.ok());
  std::vector<uint8_t> small(4 * 3 * 4, 0);
  auto added = gif->addFrame(small);
  ASSERT_FALSE(added.ok());
  EXPECT_NE(added.error().message.find("48 bytes, expected 64"), std::string::npos);
}

TEST(GifWriterValidity, UnwritablePathIsAnError) {
  auto gif = app::GifWriter::create("/nonexistent-dir/x/a.gif", 4, 4, 10);
  ASSERT_FALSE(gif.ok());
  EXPECT_NE(gif.error().message.find("/nonexistent-dir/x/a.gif"), std::string::npos);
}

// A run that stops before finish() (an error, a lost device) leaves neither
// the GIF nor its partial file; until finish() only the partial file exists.
TEST(GifWriterValidity, UnfinishedGifLeavesNoFile) {
  auto dir = testing_support::freshTempDir("gif_unfinished");
  {
    auto gif = app::GifWriter::create(dir / "a.gif", 4, 4, 10);
    ASSERT_TRUE(gif.ok()) << gif.error().message;
    ASSERT_TRUE(gif->addFrame(std::vector<uint8_t>(4 * 4 * 4, 128)).ok());
    EXPECT_FALSE(std::filesystem::exists(dir / "a.gif")) << "the GIF appears only when finished";
    EXPECT_TRUE(std::filesystem::exists(dir / "a.gif.partial"));
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "the partial file is removed";
}

TEST(GifWriterTest, WritesAnimationThatDecodesBack) {
  auto dir = testing_support::freshTempDir("gif_roundtrip");
  const int w = 32, h = 16, frames = 3;
  {
    auto gif = app::GifWriter::create(dir / "a.gif", w, h, 25);
    ASSERT_TRUE(gif.ok()) << gif.error().message;
    for (int f = 0; f < frames; ++f) {
      std::vector<uint8_t> rgba(w * h * 4, 255);
      for (int i = 0; i < w * h; ++i) rgba[i * 4 + 0] = static_cast<uint8_t>(f * 100);  // red grows per frame
      ASSERT_TRUE(gif->addFrame(rgba).ok());
    }
    ASSERT_TRUE(gif->finish().ok());
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "a.gif.partial"));
  std::ifstream in(dir / "a.gif", std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int* delays = nullptr;
  int x = 0, y = 0, z = 0, comp = 0;
  unsigned char* pixels = stbi_load_gif_from_memory(bytes.data(), static_cast<int>(bytes.size()), &delays, &x, &y,
                                                    &z, &comp, 4);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  EXPECT_EQ(x, w);
  EXPECT_EQ(y, h);
  EXPECT_EQ(z, frames);
  EXPECT_NEAR(pixels[(2 * w * h) * 4], 200, 3);  // last frame's red
  EXPECT_EQ(delays[0], 40);                      // 25 fps = 4 cs
  stbi_image_free(pixels);
  stbi_image_free(delays);
}

}  // namespace
