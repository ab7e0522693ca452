#include "engine/scene/gltf_json_prepass.h"

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_draco.h"

namespace eng {

Result<std::vector<MeshoptPlaceholder>> prepareCompressedGltf(std::span<const uint8_t> bytes, bool glb,
                                                              std::vector<uint8_t>& rewritten) {
  rewritten.clear();
  std::span<const uint8_t> json = bytes;
  GlbChunks chunks;
  if (glb) {
    auto parsed = parseGlb(bytes);
    if (!parsed) return std::vector<MeshoptPlaceholder>{};  // the loader reports the container error
    chunks = *parsed;
    json = chunks.json;
  }
  const std::string_view text(reinterpret_cast<const char*>(json.data()), json.size());
  if (text.find("_meshopt_compression") == std::string_view::npos && text.find(kKhrDraco) == std::string_view::npos)
    return std::vector<MeshoptPlaceholder>{};
  nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return std::vector<MeshoptPlaceholder>{};  // tinygltf names the JSON error

  auto placeholders = stubMeshoptPlaceholders(doc, glb && chunks.hasBin);
  if (!placeholders) return placeholders.error();
  const bool dracoChanged = stubDracoIndices(doc);
  if (placeholders->empty() && !dracoChanged) return placeholders;
  const std::string out = doc.dump();
  if (glb) rewritten = buildGlb(out, chunks.bin);
  else rewritten.assign(out.begin(), out.end());
  return placeholders;
}

}  // namespace eng
