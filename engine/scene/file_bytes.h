#pragma once
// Whole-file reads with a size cap, so a hostile path (a device, a huge file)
// is refused before anything is allocated.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "engine/core/result.h"

namespace eng {

Result<std::vector<uint8_t>> readFileBytes(const std::filesystem::path& path, size_t maxBytes);
Result<void> writeFileBytes(const std::filesystem::path& path, const void* data, size_t size);

}  // namespace eng
