#pragma once
// JSON documents from files and text, and the pieces their readers share.
// The values are read through JsonNode (json_node.h), whose errors name the
// JSON path (RFC 6901 pointer) and the problem; the reader puts the source in
// front: "data/expressions.json: /expressions/happy/actionUnits/AU13: unknown
// action unit".
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/core/result.h"

namespace facial {

// Object keys keep their file order (preset lists are shown in that order).
using Json = nlohmann::ordered_json;

inline constexpr size_t kMaxJsonFileBytes = size_t{16} << 20;

// Reads and parses a whole file; missing, unreadable, oversized or malformed
// files fail with "<path>: <problem>".
eng::Result<Json> readJsonFile(const std::filesystem::path& path, size_t maxBytes = kMaxJsonFileBytes);
// Parses text that came from `source` (a file name, "GLB JSON chunk of x.vrm").
eng::Result<Json> parseJsonText(std::string_view text, std::string_view source);

// JSON pointer of a child: childPath("/a", "b/c") == "/a/b~1c", childPath("/a", 3) == "/a/3".
std::string childPath(std::string_view parent, std::string_view key);
std::string childPath(std::string_view parent, size_t index);

// A number as people write it in messages: 1, 0.5, 100, 1e+20.
std::string formatNumber(double value);

// Fails (Unsupported) unless a file's "version" value is `supported`. A larger
// integer says the file comes from a newer release:
// "unsupported version 2: written by a newer release of facial (this build reads version 1)",
// so a newer file is refused with its version and ours, never misread.
eng::Result<void> checkFormatVersion(const Json& version, int supported);

// The JSON type as a word for messages ("string", "array", ...).
std::string_view jsonTypeName(const Json& value);

}  // namespace facial
