#pragma once
// The binary glTF container: 12-byte header, a JSON chunk, an optional BIN
// chunk. Parsing validates every length against the real byte count, so a
// truncated or forged file fails here with a precise message before any
// glTF parsing starts.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace eng {

struct GlbChunks {
  std::span<const uint8_t> json;
  std::span<const uint8_t> bin;  // empty when the file has no BIN chunk
  bool hasBin = false;
};

bool hasGlbMagic(std::span<const uint8_t> bytes);
// Messages do not name the file; the caller prefixes it.
Result<GlbChunks> parseGlb(std::span<const uint8_t> bytes);
// JSON padded with spaces, BIN with zeros, both to 4 bytes; BIN omitted when empty.
std::vector<uint8_t> buildGlb(std::string_view json, std::span<const uint8_t> bin);

}  // namespace eng
