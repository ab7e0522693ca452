#pragma once
// How deeply a JSON text nests, measured without parsing it. nlohmann::json
// (and tinygltf on top of it) parse and destroy documents recursively, so a
// hostile file of 100,000 '[' overflows the stack; every JSON text is measured
// here first and refused past a depth no real document comes near.
#include <cstddef>
#include <string_view>

#include "engine/core/result.h"

namespace eng {

// Real glTF, VRM, graph, timeline and rig-map files nest under 20 levels.
inline constexpr size_t kMaxJsonNesting = 256;

// The deepest '['/'{' nesting in `text`; brackets inside strings (escapes
// included) do not count. Linear, no recursion, no allocation; tolerates
// malformed text (the parser reports that).
size_t jsonNestingDepth(std::string_view text);

// Fails with "<source>: JSON nests N levels deep, more than the 256 accepted".
Result<void> checkJsonNesting(std::string_view text, std::string_view source, size_t limit = kMaxJsonNesting);

}  // namespace eng
