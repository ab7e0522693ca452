#include "engine/scene/gltf_extensions.h"

#include <cmath>
#include <string_view>
#include <unordered_set>

#include "engine/core/work_counter.h"
#include "engine/scene/gltf_draco.h"
#include "engine/scene/gltf_meshopt.h"
#include "engine/scene/gltf_mtoon.h"

namespace eng {
namespace {

// What a handled extension did when nothing more specific was recorded.
std::string defaultOutcome(const std::string& name) {
  if (name == kKhrMeshQuantization) return "applied: quantized accessors read as normalized/integer data";
  if (isHandledExtension(name)) return "ignored: listed, but nothing in the file uses it";
  return "ignored: not supported by this loader";
}

// A finite number property of a JSON object; `fallback` when absent.
bool numberArray(const tinygltf::Value& object, const char* name, float* out, int n) {
  if (!object.Has(name)) return true;
  const tinygltf::Value& v = object.Get(name);
  if (!v.IsArray() || v.ArrayLen() != static_cast<size_t>(n)) return false;
  for (int i = 0; i < n; ++i) {
    if (!v.Get(i).IsNumber()) return false;
    out[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
    if (!std::isfinite(out[i])) return false;
  }
  return true;
}

}  // namespace

bool isHandledExtension(const std::string& name) {
  return name == kKhrMeshQuantization || name == kExtMeshopt || name == kKhrMeshopt || name == kKhrDraco ||
         name == kExtTextureWebp || name == kKhrTextureBasisu || name == kKhrTextureTransform ||
         name == kKhrMaterialsUnlit || name == kVrmcMaterialsMtoon;
}

std::vector<ExtensionUse> describeExtensions(const tinygltf::Model& gltf, const ExtensionOutcomes& outcomes) {
  // Hashed: a file may list many thousands of names (issue 37: quadratic when each was searched for).
  const std::unordered_set<std::string_view> required(gltf.extensionsRequired.begin(), gltf.extensionsRequired.end());
  std::unordered_set<std::string_view> seen;
  std::vector<ExtensionUse> out;
  auto describe = [&](const std::string& name) {
    countWork();
    if (!seen.insert(name).second) return;
    auto it = outcomes.find(name);
    out.push_back({name, required.count(name) > 0, it != outcomes.end() ? it->second : defaultOutcome(name)});
  };
  for (const std::string& name : gltf.extensionsUsed) describe(name);
  for (const std::string& name : gltf.extensionsRequired) describe(name);
  return out;
}

int textureImageSource(const tinygltf::Texture& texture, bool& basisuOnly) {
  basisuOnly = false;
  if (auto it = texture.extensions.find(kExtTextureWebp); it != texture.extensions.end()) {
    const tinygltf::Value& ext = it->second;
    if (ext.Has("source") && ext.Get("source").IsNumber()) return ext.Get("source").GetNumberAsInt();
  }
  if (texture.source >= 0) return texture.source;
  basisuOnly = texture.extensions.count(kKhrTextureBasisu) > 0;
  return -1;
}

std::optional<UvTransform> parseTextureTransform(const tinygltf::ExtensionMap& extensions, std::string& problem) {
  problem.clear();
  auto it = extensions.find(kKhrTextureTransform);
  if (it == extensions.end()) return std::nullopt;
  const tinygltf::Value& ext = it->second;
  if (!ext.IsObject()) {
    problem = "is not an object";
    return std::nullopt;
  }
  UvTransform t;
  float rotation[1] = {0.0f};
  bool ok = numberArray(ext, "offset", &t.offset.x, 2) && numberArray(ext, "scale", &t.scale.x, 2);
  if (ext.Has("rotation")) {
    ok = ok && ext.Get("rotation").IsNumber();
    if (ok) rotation[0] = static_cast<float>(ext.Get("rotation").GetNumberAsDouble());
    ok = ok && std::isfinite(rotation[0]);
  }
  if (ext.Has("texCoord")) {
    ok = ok && ext.Get("texCoord").IsInt() && ext.Get("texCoord").GetNumberAsInt() >= 0;
    if (ok) t.texCoord = ext.Get("texCoord").GetNumberAsInt();
  }
  if (!ok) {
    problem = "has a malformed offset, rotation, scale or texCoord";
    return std::nullopt;
  }
  t.rotation = rotation[0];
  return t;
}

glm::vec2 applyUvTransform(const UvTransform& t, glm::vec2 uv) {
  // The specification's row-major matrices: translation * rotation * scale,
  // rotation = [cos sin; -sin cos].
  const float c = std::cos(t.rotation), s = std::sin(t.rotation);
  const glm::vec2 scaled = uv * t.scale;
  return glm::vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + t.offset;
}

}  // namespace eng
