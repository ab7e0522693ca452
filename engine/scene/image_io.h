#pragma once
// PNG writing (libpng) and image reading (PNG, JPEG, ... via stb), RGBA8 only.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// rgba8.size() must be w * h * 4.
Result<void> writePng(const std::filesystem::path& path, int w, int h, std::span<const uint8_t> rgba8);
// Encodes to PNG in memory (for embedding into .glb).
Result<std::vector<uint8_t>> encodePng(int w, int h, std::span<const uint8_t> rgba8);
// Images larger than this are refused before decoding (a forged header can
// claim 60000 x 60000 pixels).
inline constexpr size_t kDefaultMaxImagePixels = size_t{64} << 20;
// Vulkan guarantees 4096 and desktop GPUs give 16384 per side for 2D images.
inline constexpr uint32_t kMaxImageSide = 16384;

// Decodes any stb-supported image (PNG, JPEG, BMP, TGA, ...) or WebP (libwebp)
// to RGBA8; `name` is used in messages and becomes Image::name. KTX2 is
// recognised and refused by name (no Basis Universal transcoder in Debian).
Result<Image> decodeImage(std::span<const uint8_t> encoded, const std::string& name,
                          size_t maxPixels = kDefaultMaxImagePixels);
// The size decodeImage would make, from the header alone, with the same checks
// (a loader charges width * height * 4 bytes to its budget before decoding).
struct ImageSize {
  int width = 0, height = 0;
};
Result<ImageSize> imageSize(std::span<const uint8_t> encoded, const std::string& name,
                            size_t maxPixels = kDefaultMaxImagePixels);
bool isWebp(std::span<const uint8_t> encoded);  // RIFF....WEBP
bool isKtx2(std::span<const uint8_t> encoded);  // the 12-byte KTX 2.0 identifier
Result<Image> readImage(const std::filesystem::path& path);

}  // namespace eng
