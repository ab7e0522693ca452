#pragma once
// Animated GIF output for headless runs (programs only: libimagequant is
// GPL-3, so it stays out of the libraries an engine embeds): frames are quantised to a 256-colour
// palette each (libimagequant, with dithering) and encoded with cgif. The
// frames go to "<path>.partial" first, renamed to `path` by finish(): a run
// that stops early (an error, a lost device) leaves no half-written GIF.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "engine/core/result.h"

namespace app {

class GifWriter {
 public:
  static eng::Result<GifWriter> create(const std::filesystem::path& path, int width, int height, float framesPerSecond);
  GifWriter(GifWriter&&) noexcept;
  GifWriter& operator=(GifWriter&&) noexcept;
  ~GifWriter();  // without finish(): closes and removes the partial file

  // rgba8: width * height * 4 bytes, row 0 at the top.
  eng::Result<void> addFrame(std::span<const uint8_t> rgba8);
  // Closes the GIF and moves it to the path given to create().
  eng::Result<void> finish();

 private:
  struct Impl;
  explicit GifWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace app
