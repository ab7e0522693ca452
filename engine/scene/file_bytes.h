#pragma once
// Whole-file reads with a size cap, so a hostile path (a device, a huge file)
// is refused before anything is allocated; whole-file writes, so a failure
// never leaves half a file where a user looks (or where another process reads).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/core/result.h"

namespace eng {

Result<std::vector<uint8_t>> readFileBytes(const std::filesystem::path& path, size_t maxBytes);
// The same bytes as a string (text files: specs, label lists).
Result<std::string> readFileText(const std::filesystem::path& path, size_t maxBytes);
Result<void> writeFileBytes(const std::filesystem::path& path, const void* data, size_t size);

// The sibling a file is written to until it is complete: NAME.<pid>.partial.EXT
// (the extension kept, for writers that choose a format by it; the process id
// so two processes writing one cache file never share a partial file).
std::filesystem::path partialPathFor(const std::filesystem::path& path);
// Moves a finished partial file into place; on failure removes it, leaves
// `path` as it was and names `path`.
Result<void> commitPartialFile(const std::filesystem::path& partial, const std::filesystem::path& path);
// Writes `path` whole: `write` fills partialPathFor(path), which is committed
// when it succeeded and removed when it failed.
Result<void> writeFileWhole(const std::filesystem::path& path,
                            const std::function<Result<void>(const std::filesystem::path& partial)>& write);

}  // namespace eng
