#include "engine/scene/glb_container.h"

#include <cstring>
#include <string>

namespace eng {
namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

uint32_t readU32(const uint8_t* p) {
  // GLB is little-endian, as is every platform we build for.
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void appendU32(std::vector<uint8_t>& out, uint32_t v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + 4);
}

std::string printableTag(const uint8_t* p) {
  std::string s;
  for (int i = 0; i < 4; ++i) s += (p[i] >= 32 && p[i] < 127) ? static_cast<char>(p[i]) : '?';
  return s;
}

}  // namespace

bool hasGlbMagic(std::span<const uint8_t> bytes) { return bytes.size() >= 4 && readU32(bytes.data()) == kMagic; }

Result<GlbChunks> parseGlb(std::span<const uint8_t> bytes) {
  const size_t size = bytes.size();
  if (size < 4) return makeError(ErrorKind::Malformed, "truncated GLB: " + std::to_string(size) + " bytes, not even a magic number");
  if (!hasGlbMagic(bytes))
    return makeError(ErrorKind::Malformed, "wrong magic '" + printableTag(bytes.data()) + "' (a .glb starts with 'glTF')");
  if (size < 12) return makeError(ErrorKind::Malformed, "truncated GLB: " + std::to_string(size) + " bytes, the header needs 12");
  const uint32_t version = readU32(bytes.data() + 4);
  if (version != 2) return makeError(ErrorKind::Unsupported, "GLB container version " + std::to_string(version) + " is not supported (need 2)");
  const uint32_t length = readU32(bytes.data() + 8);
  if (length > size)
    return makeError(ErrorKind::Malformed, "truncated GLB: header declares " + std::to_string(length) + " bytes, file has " +
                     std::to_string(size));
  if (length < 20) return makeError(ErrorKind::Malformed, "corrupt GLB: declared length " + std::to_string(length) + " leaves no room for a JSON chunk");

  GlbChunks chunks;
  size_t offset = 12;
  int index = 0;
  while (offset < length) {
    if (length - offset < 8)
      return makeError(ErrorKind::Malformed, "truncated GLB: chunk " + std::to_string(index) + " header at byte " + std::to_string(offset) +
                       " runs past the declared length " + std::to_string(length));
    const uint32_t chunkLength = readU32(bytes.data() + offset);
    const uint32_t chunkType = readU32(bytes.data() + offset + 4);
    const size_t dataBegin = offset + 8;
    if (chunkLength > length - dataBegin)
      return makeError(ErrorKind::Malformed, "truncated GLB: chunk " + std::to_string(index) + " ('" + printableTag(bytes.data() + offset + 4) +
                       "') of " + std::to_string(chunkLength) + " bytes at byte " + std::to_string(dataBegin) +
                       " runs past the declared length " + std::to_string(length));
    const std::span<const uint8_t> data = bytes.subspan(dataBegin, chunkLength);
    if (index == 0) {
      if (chunkType != kChunkJson)
        return makeError(ErrorKind::Malformed, "corrupt GLB: first chunk is '" + printableTag(bytes.data() + offset + 4) + "', expected 'JSON'");
      if (chunkLength == 0) return makeError(ErrorKind::Malformed, "corrupt GLB: JSON chunk is empty");
      chunks.json = data;
    } else if (index == 1 && chunkType == kChunkBin) {
      chunks.bin = data;
      chunks.hasBin = true;
    } else if (chunkType == kChunkJson || chunkType == kChunkBin) {
      return makeError(ErrorKind::Malformed, "corrupt GLB: chunk " + std::to_string(index) + " is a second '" +
                       printableTag(bytes.data() + offset + 4) + "' chunk");
    }
    // Unknown chunk types are skipped, as the spec requires.
    offset = dataBegin + ((static_cast<size_t>(chunkLength) + 3) & ~size_t{3});
    ++index;
  }
  return chunks;
}

std::vector<uint8_t> buildGlb(std::string_view json, std::span<const uint8_t> bin) {
  const size_t jsonPadded = (json.size() + 3) & ~size_t{3};
  const size_t binPadded = (bin.size() + 3) & ~size_t{3};
  const size_t total = 12 + 8 + jsonPadded + (bin.empty() ? 0 : 8 + binPadded);
  std::vector<uint8_t> out;
  out.reserve(total);
  appendU32(out, kMagic);
  appendU32(out, 2);
  appendU32(out, static_cast<uint32_t>(total));
  appendU32(out, static_cast<uint32_t>(jsonPadded));
  appendU32(out, kChunkJson);
  out.insert(out.end(), json.begin(), json.end());
  out.resize(out.size() + (jsonPadded - json.size()), ' ');
  if (!bin.empty()) {
    appendU32(out, static_cast<uint32_t>(binPadded));
    appendU32(out, kChunkBin);
    out.insert(out.end(), bin.begin(), bin.end());
    out.resize(out.size() + (binPadded - bin.size()), 0);
  }
  return out;
}

}  // namespace eng
