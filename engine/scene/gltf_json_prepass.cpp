#include "engine/scene/gltf_json_prepass.h"

#include <algorithm>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_draco.h"
#include "engine/scene/model.h"

namespace eng {
namespace {

// What one entry of a top-level array holds once parsed (tinygltf's object,
// the Model's where it makes one, and the parser's JSON value); entries of
// arrays not listed cost only the JSON value.
constexpr size_t kJsonValueBytes = 64;
size_t entryBytes(std::string_view key) {
  struct Cost {
    std::string_view key;
    size_t bytes;
  };
  static constexpr Cost kCosts[] = {
      {"accessors", sizeof(tinygltf::Accessor)},
      {"animations", sizeof(tinygltf::Animation) + sizeof(Animation)},
      {"buffers", sizeof(tinygltf::Buffer)},
      {"bufferViews", sizeof(tinygltf::BufferView)},
      {"cameras", sizeof(tinygltf::Camera)},
      {"images", sizeof(tinygltf::Image) + sizeof(Image)},
      {"materials", sizeof(tinygltf::Material) + sizeof(Material)},
      {"meshes", sizeof(tinygltf::Mesh) + sizeof(Mesh)},
      {"nodes", sizeof(tinygltf::Node) + sizeof(Node)},
      {"samplers", sizeof(tinygltf::Sampler)},
      {"scenes", sizeof(tinygltf::Scene)},
      {"skins", sizeof(tinygltf::Skin) + sizeof(Skin)},
      {"textures", sizeof(tinygltf::Texture)},
  };
  for (const Cost& cost : kCosts)
    if (cost.key == key) return cost.bytes + kJsonValueBytes;
  return kJsonValueBytes;
}

}  // namespace

Result<void> chargeGltfObjects(std::string_view json, LoadBudget& budget) {
  // depth counts open containers; the entries of the array at depth 2 belong
  // to the top-level key read last.
  int depth = 0;
  std::string_view key, lastString;
  size_t entries = 0;
  bool arrayOpen = false, expectEntry = false;
  auto close = [&]() -> Result<void> {
    arrayOpen = false;
    if (entries == 0) return {};
    return budget.charge(entries, entryBytes(key), std::to_string(entries) + " " + std::string(key.substr(0, 40)));
  };
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    if (depth == 2 && arrayOpen && expectEntry && c != ']') {
      ++entries;
      expectEntry = false;
    }
    if (c == '"') {
      const size_t start = ++i;
      while (i < json.size() && json[i] != '"') i += json[i] == '\\' ? 2 : 1;
      lastString = json.substr(start, std::min(i, json.size()) - start);
    } else if (c == ':' && depth == 1) {
      key = lastString;
    } else if (c == '[' || c == '{') {
      if (++depth == 2 && c == '[') arrayOpen = expectEntry = true, entries = 0;
    } else if (c == ']' || c == '}') {
      if (depth-- == 2 && arrayOpen)
        if (auto ok = close(); !ok) return ok;
    } else if (c == ',' && depth == 2 && arrayOpen) {
      expectEntry = true;
    }
  }
  return {};
}

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
