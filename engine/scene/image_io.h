#pragma once
// PNG writing and image reading (PNG, JPEG, ... via stb), RGBA8 only.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// rgba8.size() must be w * h * 4.
Result<void> writePng(const std::filesystem::path& path, int w, int h, std::span<const uint8_t> rgba8);
// Encodes to PNG in memory (for embedding into .glb).
Result<std::vector<uint8_t>> encodePng(int w, int h, std::span<const uint8_t> rgba8);
// Decodes any stb-supported image to RGBA8; `name` is used in messages and Image::name.
Result<Image> decodeImage(std::span<const uint8_t> encoded, const std::string& name);
Result<Image> readImage(const std::filesystem::path& path);

}  // namespace eng
