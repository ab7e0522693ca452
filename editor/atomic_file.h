#pragma once
// Saving without ever leaving a half-written file behind: the content goes to
// a temporary sibling first and replaces the target by rename() only once it
// is complete, so a failed save keeps the previous file intact.
#include <filesystem>
#include <functional>

#include "engine/core/result.h"
#include "facial/runtime/json/json_document.h"

namespace editor {

// The temporary sibling a save writes first: "<stem>.saving<ext>" (the same
// extension, so writers that pick a format by extension still see it).
std::filesystem::path temporarySibling(const std::filesystem::path& path);

// Calls write(temporarySibling(path)); on success renames it over `path`, on
// failure removes it and returns the writer's error. Errors name `path`.
eng::Result<void> replaceFileAtomically(const std::filesystem::path& path,
                                        const std::function<eng::Result<void>(const std::filesystem::path&)>& write);

// A JSON document (indented one space a level) written through replaceFileAtomically.
eng::Result<void> writeJsonAtomically(const facial::Json& json, const std::filesystem::path& path);

}  // namespace editor
