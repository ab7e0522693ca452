#pragma once
// Animated GIF output for headless runs: frames are quantised to a 256-colour
// palette each (libimagequant, with dithering) and encoded with cgif.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "engine/core/result.h"

namespace eng {

class GifWriter {
 public:
  static Result<GifWriter> create(const std::filesystem::path& path, int width, int height, float framesPerSecond);
  GifWriter(GifWriter&&) noexcept;
  GifWriter& operator=(GifWriter&&) noexcept;
  ~GifWriter();  // closes the file if finish() was not called

  // rgba8: width * height * 4 bytes, row 0 at the top.
  Result<void> addFrame(std::span<const uint8_t> rgba8);
  Result<void> finish();

 private:
  struct Impl;
  explicit GifWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace eng
