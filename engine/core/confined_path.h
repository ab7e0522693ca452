#pragma once
// Files named inside other files (a graph's timelines, an OBJ's materials)
// stay in the folder of the file that names them: a downloaded file must not
// make the program read from anywhere on the disk.
#include <filesystem>
#include <string_view>

#include "engine/core/result.h"

namespace eng {

// `path` is `folder` or lies below it, compared component by component; both
// absolute and normalised (lexically_normal or weakly_canonical).
bool isInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder);

// `name` resolved in `folder` (any form; the result is absolute): refused when it is
// absolute, when its `..` leave the folder, or when a link inside the folder
// resolves outside it. The error names `name` only (it is the naming file's
// text), never what the refused path holds.
Result<std::filesystem::path> resolveInsideFolder(const std::filesystem::path& folder, std::string_view name);

// `path` made absolute, with links and `..` resolved as far as it exists.
std::filesystem::path resolvedPath(const std::filesystem::path& path);

}  // namespace eng
