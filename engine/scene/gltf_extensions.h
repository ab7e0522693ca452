#pragma once
// Which glTF extensions the loader honours and how: the list a file's
// extensionsRequired is checked against, the texture-level extensions
// (EXT_texture_webp, KHR_texture_basisu, KHR_texture_transform), and the
// per-extension record `facial info` prints. The geometry decoders live in
// gltf_meshopt.* and gltf_draco.*.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "engine/scene/model.h"

namespace eng {

inline constexpr const char* kKhrMeshQuantization = "KHR_mesh_quantization";
inline constexpr const char* kExtTextureWebp = "EXT_texture_webp";
inline constexpr const char* kKhrTextureBasisu = "KHR_texture_basisu";
inline constexpr const char* kKhrTextureTransform = "KHR_texture_transform";
inline constexpr const char* kKhrMaterialsUnlit = "KHR_materials_unlit";

// Extensions a file may require and still load: decoded, applied, or (KTX2
// textures) skipped with a warning while the model itself stays correct.
bool isHandledExtension(const std::string& name);

// What was done with each extension, filled while loading: name -> outcome.
using ExtensionOutcomes = std::map<std::string, std::string>;

// The file's extensionsUsed (then any extensionsRequired missing from it),
// each with its outcome; extensions nothing was recorded for get a default
// ("ignored: ..." for unknown ones).
std::vector<ExtensionUse> describeExtensions(const tinygltf::Model& gltf, const ExtensionOutcomes& outcomes);

// The image a texture shows: EXT_texture_webp's source when present, else
// the core `source`. -1 when there is none we can decode; `basisuOnly` tells
// that the texture had only a KHR_texture_basisu (KTX2) source.
int textureImageSource(const tinygltf::Texture& texture, bool& basisuOnly);

// KHR_texture_transform on a textureInfo: uv' = T(offset) * R(rotation) * S(scale) * uv.
struct UvTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians, counter-clockwise in UV space
  glm::vec2 scale{1.0f};
  int texCoord = -1;  // -1: the textureInfo's own set
};
// nullopt when the textureInfo's extensions have no (usable) transform;
// `problem` is set when one is present but malformed.
std::optional<UvTransform> parseTextureTransform(const tinygltf::ExtensionMap& extensions, std::string& problem);
glm::vec2 applyUvTransform(const UvTransform& t, glm::vec2 uv);

}  // namespace eng
