#include "engine/scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <cstdio>
#include <optional>
#include <sstream>

#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "engine/core/json_nesting.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_accessor_reader.h"
#include "engine/scene/gltf_draco.h"
#include "engine/scene/gltf_extensions.h"
#include "engine/scene/gltf_file_access.h"
#include "engine/scene/gltf_json_prepass.h"
#include "engine/scene/gltf_meshopt.h"
#include "engine/scene/gltf_skin_reader.h"
#include "engine/scene/image_io.h"
#include "engine/scene/normals.h"

namespace eng {
namespace {

// tinygltf's error text as one readable line: newlines joined, the JSON
// library's exception tag replaced, embedded data: URIs shortened.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      out += "; ";
    } else if (c == '[' && text.compare(i, 16, "[json.exception.") == 0 && text.find("] ", i) != std::string::npos) {
      out += "invalid JSON: ";
      i = text.find("] ", i) + 1;
    } else if (c == 'd' && text.compare(i, 5, "data:") == 0) {
      size_t end = i;
      while (end < text.size() && text[end] != ' ' && text[end] != '\n') ++end;
      out += end - i > 40 ? text.substr(i, 40) + "..." : text.substr(i, end - i);
      i = end - 1;
    } else if (c != '\r') {
      out += c;
    }
  }
  return out;
}

// glTF versions are "<major>.<minor>": a 2.x asset loads (minor versions stay
// compatible) unless its minVersion asks for more than 2.0; another major
// version is a different format. Both are refused by name, never misread.
std::optional<Error> assetVersionProblem(const tinygltf::Asset& asset) {
  const auto parse = [](const std::string& text, int& major, int& minor) {
    return std::sscanf(text.c_str(), "%d.%d", &major, &minor) == 2;
  };
  int major = 0, minor = 0;
  if (!parse(asset.version, major, minor))
    return makeError(ErrorKind::Malformed, "asset.version '" + asset.version + "' is not a glTF version (expected 2.0)");
  if (major != 2)
    return makeError(ErrorKind::Unsupported, "glTF version " + asset.version + " is not supported (this loader reads glTF 2.x)");
  if (!asset.minVersion.empty()) {
    if (!parse(asset.minVersion, major, minor))
      return makeError(ErrorKind::Malformed, "asset.minVersion '" + asset.minVersion + "' is not a glTF version");
    if (major != 2 || minor > 0)
      return makeError(ErrorKind::Unsupported, "the file needs glTF " + asset.minVersion +
                                                   " (asset.minVersion), newer than the 2.0 this loader reads");
  }
  return std::nullopt;
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// tinygltf's image hook: keep the encoded bytes and decode later with our own
// limits, so one broken image becomes a warning instead of a failed load.
// It also checks what tinygltf does not: that an image's bufferView fits its buffer.
struct ImageHookContext {
  const tinygltf::Model* gltf = nullptr;
};

bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
  const auto* ctx = static_cast<const ImageHookContext*>(user);
  if (image->bufferView >= 0) {
    const tinygltf::Model& gltf = *ctx->gltf;
    const auto& bv = gltf.bufferViews[static_cast<size_t>(image->bufferView)];
    const size_t bufferSize = gltf.buffers[static_cast<size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset) {
      if (err)
        *err += "image " + std::to_string(index) + ": bufferView " + std::to_string(image->bufferView) + " (bytes " +
                std::to_string(bv.byteOffset) + ".." + std::to_string(bv.byteOffset + bv.byteLength) +
                ") is out of range of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(bufferSize) +
                " bytes)\n";
      return false;
    }
  }
  if (size < 0) return false;
  image->image.assign(bytes, bytes + size);
  image->width = image->height = image->component = -1;  // still encoded
  return true;
}

class ModelBuilder {
 public:
  ModelBuilder(std::string file, const tinygltf::Model& gltf, const GltfLoadLimits& limits,
               const GltfFileAccess& files, ExtensionOutcomes& outcomes)
      : file_(std::move(file)), gltf_(gltf), limits_(limits), files_(files), outcomes_(outcomes),
        reader_(gltf, limits.maxDecodedBytes) {}

  Result<Model> build() {
    model_.sourcePath = file_;
    if (auto ok = checkExtensions(); !ok) return ok.error();
    if (auto ok = loadImages(); !ok) return ok.error();
    loadMaterials();
    for (size_t m = 0; m < gltf_.meshes.size(); ++m)
      if (auto ok = loadMesh(static_cast<int>(m)); !ok) return ok.error();
    if (auto ok = loadNodes(); !ok) return ok.error();
    if (auto ok = readSkins(reader_, gltf_, model_); !ok) return fail(ok.error());
    if (auto ok = loadAnimations(); !ok) return ok.error();
    return std::move(model_);
  }

 private:
  Error fail(const std::string& message, ErrorKind kind = ErrorKind::Malformed) const {
    return makeError(kind, file_ + ": " + message);
  }
  // A failure of a reader that does not know the file name: same kind, with the file in front.
  Error fail(const Error& inner) const { return inner.prefixed(file_ + ": "); }
  void warn(std::string message) { model_.warnings.push_back(std::move(message)); }

  std::string meshLabel(int m) const {
    const std::string& name = gltf_.meshes[m].name;
    return "mesh " + std::to_string(m) + (name.empty() ? "" : " '" + name + "'");
  }

  Result<void> checkExtensions() {
    for (const std::string& ext : gltf_.extensionsRequired)
      if (!isHandledExtension(ext))
        return fail("requires glTF extension " + ext + ", which this loader does not support", ErrorKind::Unsupported);
    for (const std::string& ext : gltf_.extensionsUsed) {
      const bool required =
          std::find(gltf_.extensionsRequired.begin(), gltf_.extensionsRequired.end(), ext) != gltf_.extensionsRequired.end();
      if (!required && !isHandledExtension(ext)) warn("optional extension " + ext + " ignored");
    }
    return {};
  }

  Result<void> loadImages() {
    imageRemap_.assign(gltf_.images.size(), -1);
    for (size_t i = 0; i < gltf_.images.size(); ++i) {
      const tinygltf::Image& src = gltf_.images[i];
      const std::string label = src.uri.empty() || isDataUri(src.uri) ? (src.name.empty() ? "embedded" : src.name) : src.uri;
      if (src.image.empty()) {
        if (!src.uri.empty() && !isDataUri(src.uri)) {
          // tinygltf only warns about an unreadable image file; a face without
          // its texture is a broken asset, so this is fatal.
          std::string why = files_.problemFor(src.uri);
          if (why.empty() && !files_.problems().empty()) why = files_.problems().back();
          if (why.empty()) why = "image file '" + src.uri + "' could not be read";
          return fail("image " + std::to_string(i) + ": " + why);
        }
        warn("image " + std::to_string(i) + " ('" + label + "') has no data; skipped");
        continue;
      }
      if (isKtx2(src.image) || src.mimeType == "image/ktx2") {
        warn("image " + std::to_string(i) + " ('" + label + "') is KTX2 (" + kKhrTextureBasisu +
             "), which this build cannot transcode; skipped, its materials keep their factors");
        outcomes_[kKhrTextureBasisu] = "skipped: " + std::to_string(++ktx2Skipped_) +
                                       " KTX2 image(s), no Basis Universal transcoder in Debian; factors kept";
        continue;
      }
      auto decoded = decodeImage(src.image, label, limits_.maxImagePixels);
      if (decoded && isWebp(src.image))
        outcomes_[kExtTextureWebp] = "decoded: " + std::to_string(++webpDecoded_) + " WebP image(s) (libwebp)";
      if (!decoded) {
        warn("image " + std::to_string(i) + " skipped: " + decoded.error().message);
        continue;
      }
      imageRemap_[i] = static_cast<int>(model_.images.size());
      model_.images.push_back(std::move(*decoded));
    }
    return {};
  }

  int imageOfTexture(int texture, const std::string& where) {
    if (texture < 0) return -1;
    if (static_cast<size_t>(texture) >= gltf_.textures.size()) {
      warn(where + " refers to texture " + std::to_string(texture) + ", the file has " +
           std::to_string(gltf_.textures.size()) + "; ignored");
      return -1;
    }
    bool basisuOnly = false;
    const int source = textureImageSource(gltf_.textures[texture], basisuOnly);
    if (basisuOnly)
      warn(where + ": texture " + std::to_string(texture) + " has only a " + kKhrTextureBasisu +
           " (KTX2) source, which this build cannot decode; the material keeps its factors");
    if (source < 0) return -1;
    if (static_cast<size_t>(source) >= imageRemap_.size()) {
      warn(where + ": texture " + std::to_string(texture) + " refers to image " + std::to_string(source) +
           ", the file has " + std::to_string(imageRemap_.size()) + "; ignored");
      return -1;
    }
    return imageRemap_[source];
  }

  int modelImage(int gltfImage, const std::string& where) {
    if (gltfImage < 0 || static_cast<size_t>(gltfImage) >= imageRemap_.size()) {
      warn(where + " refers to image " + std::to_string(gltfImage) + ", the file has " +
           std::to_string(imageRemap_.size()) + "; ignored");
      return -1;
    }
    return imageRemap_[gltfImage];
  }

  void loadMaterials() {
    for (size_t i = 0; i < gltf_.materials.size(); ++i) {
      const tinygltf::Material& src = gltf_.materials[i];
      const std::string where = "material " + std::to_string(i);
      Material mat;
      mat.name = src.name;
      const auto& pbr = src.pbrMetallicRoughness;
      if (pbr.baseColorFactor.size() == 4)
        mat.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                        pbr.baseColorFactor[3]);
      mat.baseColorImage = imageOfTexture(pbr.baseColorTexture.index, where);
      uvTransforms_.push_back(baseColorUvTransform(pbr.baseColorTexture, mat.baseColorImage, where));
      mat.roughness = static_cast<float>(pbr.roughnessFactor);
      mat.metallic = static_cast<float>(pbr.metallicFactor);
      mat.doubleSided = src.doubleSided;
      if (src.emissiveFactor.size() == 3)
        mat.emissiveFactor = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
      if (!std::isfinite(mat.roughness) || !std::isfinite(mat.metallic) ||
          glm::any(glm::isnan(mat.baseColorFactor)) || glm::any(glm::isinf(mat.baseColorFactor)) ||
          glm::any(glm::isnan(mat.emissiveFactor)) || glm::any(glm::isinf(mat.emissiveFactor))) {
        warn(where + " has non-finite factors; defaults used");
        mat.baseColorFactor = glm::vec4(1.0f);
        mat.emissiveFactor = glm::vec3(0.0f);
        mat.roughness = 1.0f;
        mat.metallic = 1.0f;
      }
      // Emission is drawn from the factor alone: with a texture masking it,
      // the factor would light the whole surface, so it is left out.
      if (src.emissiveTexture.index >= 0 && mat.emissiveFactor != glm::vec3(0.0f)) {
        warn(where + " has an emissiveTexture, which is not drawn; its emission is left out");
        mat.emissiveFactor = glm::vec3(0.0f);
      }
      if (src.extras.IsObject() && src.extras.Has("detailLayers")) {
        const tinygltf::Value& layers = src.extras.Get("detailLayers");
        for (size_t l = 0; layers.IsArray() && l < layers.ArrayLen(); ++l) {
          const tinygltf::Value& layer = layers.Get(static_cast<int>(l));
          const std::string lw = where + " detail layer " + std::to_string(l);
          if (!layer.IsObject() || !layer.Has("image") || !layer.Get("image").IsNumber() || !layer.Has("target") ||
              !layer.Get("target").IsString()) {
            warn(lw + " needs an integer 'image' and a string 'target'; ignored");
            continue;
          }
          DetailLayer d;
          d.image = modelImage(layer.Get("image").GetNumberAsInt(), lw);
          d.target = layer.Get("target").Get<std::string>();
          if (layer.Has("strength") && layer.Get("strength").IsNumber())
            d.strength = static_cast<float>(layer.Get("strength").GetNumberAsDouble());
          if (d.image < 0 || !std::isfinite(d.strength)) {
            warn(lw + " has no usable image or strength; ignored");
            continue;
          }
          mat.detailLayers.push_back(std::move(d));
        }
      }
      model_.materials.push_back(std::move(mat));
    }
  }

  // Triangle list from the primitive's vertex order (indices or 0..n-1) and mode.
  static std::vector<uint32_t> triangulate(const std::vector<uint32_t>& order, int mode) {
    std::vector<uint32_t> tris;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      tris.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(order.size() / 3 * 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < order.size(); ++i) {
        // Every other strip triangle is flipped to keep one winding.
        if (i % 2 == 0) tris.insert(tris.end(), {order[i], order[i + 1], order[i + 2]});
        else tris.insert(tris.end(), {order[i + 1], order[i], order[i + 2]});
      }
    } else {  // fan
      for (size_t i = 1; i + 1 < order.size(); ++i) tris.insert(tris.end(), {order[0], order[i], order[i + 1]});
    }
    return tris;
  }

  template <int N>
  Result<std::vector<glm::vec<N, float>>> readAttribute(int accessor, size_t expectedCount, const std::string& what) {
    auto values = reader_.readVec<N>(accessor, what);
    if (!values) return fail(values.error());
    if (expectedCount != SIZE_MAX && values->size() != expectedCount)
      return fail(what + " has " + std::to_string(values->size()) + " elements, its primitive has " +
                  std::to_string(expectedCount) + " vertices");
    return values;
  }

  // What a primitive of `vertices` vertices makes beyond its accessors (generated
  // normals, the 0..n-1 order of a non-indexed primitive, the triangle list,
  // normals for each generated-normal target) counts against the decode budget
  // too, and is charged before anything is read: an accessor without a
  // bufferView declares any count in a few bytes of JSON (zero-filled per the
  // spec), and everything made from it is as large.
  Result<void> chargeDerivedData(const tinygltf::Primitive& src, int mode, size_t vertices, const std::string& label) {
    constexpr size_t kVec3 = sizeof(glm::vec3), kIndex = sizeof(uint32_t);
    size_t order = vertices;
    if (src.indices >= 0) {
      auto count = reader_.count(src.indices, label + " indices");
      if (!count) return fail(count.error());
      order = std::min(*count, SIZE_MAX / 64);
    }
    const size_t triangleIndices = mode == TINYGLTF_MODE_TRIANGLES ? order / 3 * 3 : order < 3 ? 0 : 3 * (order - 2);
    size_t bytes = triangleIndices * kIndex + (src.indices >= 0 ? 0 : vertices * kIndex);
    if (src.attributes.count("NORMAL") == 0) {
      const size_t morphedNormals = static_cast<size_t>(std::count_if(
          src.targets.begin(), src.targets.end(), [](const auto& target) { return target.count("POSITION") != 0; }));
      bytes += (1 + std::min(morphedNormals, size_t{1} << 20)) * vertices * kVec3;  // min: no overflow
    }
    auto ok = reader_.charge(bytes, label + " POSITION (accessor " + std::to_string(src.attributes.at("POSITION")) +
                                        ", " + std::to_string(vertices) + " vertices): the normals and indices made for it");
    if (!ok) return fail(ok.error());
    return {};
  }

  // Returns false (with a warning) for primitives we skip.
  Result<bool> loadPrimitive(int m, int p, Primitive& out, size_t& targetCount, bool& targetCountKnown) {
    const tinygltf::Primitive& src = gltf_.meshes[m].primitives[p];
    const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
    const int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      warn(label + " has mode " + std::to_string(mode) + " (points or lines); skipped");
      return false;
    }
    const auto posIt = src.attributes.find("POSITION");
    if (posIt == src.attributes.end()) {
      warn(label + " has no POSITION attribute; skipped");
      return false;
    }
    if (auto declared = reader_.count(posIt->second, label + " POSITION"); !declared) {
      return fail(declared.error());
    } else if (*declared > UINT32_MAX) {
      return fail(label + " has " + std::to_string(*declared) + " vertices, more than 32-bit indices address", ErrorKind::TooLarge);
    } else if (auto ok = chargeDerivedData(src, mode, *declared, label); !ok) {
      return ok.error();
    }
    auto positions = readAttribute<3>(posIt->second, SIZE_MAX, label + " POSITION");
    if (!positions) return positions.error();
    out.positions = std::move(*positions);
    const size_t n = out.positions.size();
    if (n == 0) {
      warn(label + " has no vertices; skipped");
      return false;
    }

    bool generatedNormals = false;
    if (auto it = src.attributes.find("NORMAL"); it != src.attributes.end()) {
      auto normals = readAttribute<3>(it->second, n, label + " NORMAL");
      if (!normals) return normals.error();
      out.normals = std::move(*normals);
    } else {
      generatedNormals = true;
    }
    if (auto it = src.attributes.find("TEXCOORD_0"); it != src.attributes.end()) {
      auto uvs = readAttribute<2>(it->second, n, label + " TEXCOORD_0");
      if (!uvs) return uvs.error();
      out.texcoords = std::move(*uvs);
    }
    if (auto it = src.attributes.find("TANGENT"); it != src.attributes.end()) {
      auto tangents = readAttribute<4>(it->second, n, label + " TANGENT");
      if (!tangents) return tangents.error();
      out.tangents = std::move(*tangents);
    }
    if (auto ok = readSkinAttributes(reader_, gltf_, src, label, out, model_.warnings); !ok)
      return fail(ok.error());

    std::vector<uint32_t> order;
    if (src.indices >= 0) {
      auto indices = reader_.readIndices(src.indices, label + " indices");
      if (!indices) return fail(indices.error());
      for (size_t i = 0; i < indices->size(); ++i)
        if ((*indices)[i] >= n)
          return fail(label + ": index " + std::to_string((*indices)[i]) + " at position " + std::to_string(i) +
                      " is out of range of " + std::to_string(n) + " vertices");
      order = std::move(*indices);
    } else {
      order.resize(n);
      for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && order.size() % 3 != 0)
      warn(label + " has " + std::to_string(order.size()) + " indices, not a multiple of 3; the last " +
           std::to_string(order.size() % 3) + " ignored");
    out.indices = triangulate(order, mode);
    if (generatedNormals) out.normals = computeSmoothNormals(out.positions, out.indices);

    if (src.material >= 0 && static_cast<size_t>(src.material) >= model_.materials.size()) {
      warn(label + " refers to material " + std::to_string(src.material) + ", the file has " +
           std::to_string(model_.materials.size()) + "; default material used");
      out.material = -1;
    } else {
      out.material = src.material;
    }
    // KHR_texture_transform baked into this primitive's own copy of TEXCOORD_0.
    if (out.material >= 0 && uvTransforms_[out.material])
      for (glm::vec2& uv : out.texcoords) uv = applyUvTransform(*uvTransforms_[out.material], uv);

    if (!targetCountKnown) {
      targetCount = src.targets.size();
      targetCountKnown = true;
    } else if (src.targets.size() != targetCount) {
      return fail(label + " has " + std::to_string(src.targets.size()) + " morph targets, the mesh's other primitives have " +
                  std::to_string(targetCount));
    }
    out.targets.resize(src.targets.size());
    bool warnedOther = false;
    for (size_t t = 0; t < src.targets.size(); ++t) {
      MorphTarget& target = out.targets[t];
      for (const auto& [semantic, accessor] : src.targets[t]) {
        const std::string what = label + " target " + std::to_string(t) + " " + semantic;
        if (semantic == "POSITION" || semantic == "NORMAL" || semantic == "TANGENT") {
          auto deltas = readAttribute<3>(accessor, n, what);
          if (!deltas) return deltas.error();
          (semantic == "POSITION" ? target.positions : semantic == "NORMAL" ? target.normals : target.tangents) =
              std::move(*deltas);
        } else if (!warnedOther) {
          warn(label + " morphs " + semantic + ", which is ignored (only POSITION, NORMAL, TANGENT are morphed)");
          warnedOther = true;
        }
      }
      // Normals we made up must follow the shape too: derive their deltas
      // from the fully applied target.
      if (generatedNormals && !target.positions.empty()) {
        std::vector<glm::vec3> moved(n);
        for (size_t v = 0; v < n; ++v) moved[v] = out.positions[v] + target.positions[v];
        target.normals = computeSmoothNormals(moved, out.indices);
        for (size_t v = 0; v < n; ++v) target.normals[v] -= out.normals[v];
      }
    }
    return true;
  }

  Result<void> loadMesh(int m) {
    const tinygltf::Mesh& src = gltf_.meshes[m];
    Mesh mesh;
    mesh.name = src.name;
    size_t targetCount = 0;
    bool targetCountKnown = false;
    for (size_t p = 0; p < src.primitives.size(); ++p) {
      Primitive prim;
      auto kept = loadPrimitive(m, static_cast<int>(p), prim, targetCount, targetCountKnown);
      if (!kept) return kept.error();
      if (*kept) mesh.primitives.push_back(std::move(prim));
    }
    if (!targetCountKnown) targetCount = src.weights.size();

    std::vector<std::string> names;
    if (src.extras.IsObject() && src.extras.Has("targetNames")) {
      const tinygltf::Value& list = src.extras.Get("targetNames");
      bool allStrings = list.IsArray();
      for (size_t i = 0; allStrings && i < list.ArrayLen(); ++i) {
        const tinygltf::Value& v = list.Get(static_cast<int>(i));
        if (!v.IsString()) allStrings = false;
        else names.push_back(v.Get<std::string>());
      }
      if (!allStrings || names.size() != targetCount) {
        warn(meshLabel(m) + ": extras.targetNames is not a list of " + std::to_string(targetCount) +
             " strings; names target_N used");
        names.clear();
      }
    }
    if (names.empty())
      for (size_t t = 0; t < targetCount; ++t) names.push_back("target_" + std::to_string(t));
    mesh.targetNames = std::move(names);

    mesh.defaultWeights.assign(targetCount, 0.0f);
    if (!src.weights.empty()) {
      if (src.weights.size() != targetCount) {
        warn(meshLabel(m) + " has " + std::to_string(src.weights.size()) + " default weights for " +
             std::to_string(targetCount) + " targets; zeros used");
      } else {
        for (size_t t = 0; t < targetCount; ++t) {
          const float w = static_cast<float>(src.weights[t]);
          if (!std::isfinite(w)) return fail(meshLabel(m) + ": default weight " + std::to_string(t) + " is not finite");
          mesh.defaultWeights[t] = w;
        }
      }
    }
    model_.meshes.push_back(std::move(mesh));
    return {};
  }

  Result<void> loadNodes() {
    const size_t count = gltf_.nodes.size();
    model_.nodes.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const tinygltf::Node& src = gltf_.nodes[i];
      Node& node = model_.nodes[i];
      const std::string label = "node " + std::to_string(i) + (src.name.empty() ? "" : " '" + src.name + "'");
      node.name = src.name;
      if (src.mesh >= 0 && static_cast<size_t>(src.mesh) >= model_.meshes.size())
        return fail(label + " refers to mesh " + std::to_string(src.mesh) + ", the file has " +
                    std::to_string(model_.meshes.size()));
      node.mesh = src.mesh;
      bool finite = true;
      auto num = [&](double v) {
        finite = finite && std::isfinite(v);
        return static_cast<float>(v);
      };
      if (src.matrix.size() == 16) {
        node.hasMatrix = true;
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) node.matrix[c][r] = num(src.matrix[c * 4 + r]);  // column-major, like glm
      } else {
        if (src.translation.size() == 3)
          node.translation = glm::vec3(num(src.translation[0]), num(src.translation[1]), num(src.translation[2]));
        if (src.rotation.size() == 4)
          node.rotation = glm::quat(num(src.rotation[3]), num(src.rotation[0]), num(src.rotation[1]), num(src.rotation[2]));
        if (src.scale.size() == 3) node.scale = glm::vec3(num(src.scale[0]), num(src.scale[1]), num(src.scale[2]));
      }
      if (!finite) return fail(label + " has a non-finite transform");
      for (int child : src.children) {
        if (child < 0 || static_cast<size_t>(child) >= count)
          return fail(label + " has child " + std::to_string(child) + ", the file has " + std::to_string(count) + " nodes");
        if (static_cast<size_t>(child) == i) return fail(label + " is its own child");
        node.children.push_back(child);
      }
    }
    for (size_t i = 0; i < count; ++i)
      for (int child : model_.nodes[i].children) {
        Node& c = model_.nodes[child];
        if (c.parent >= 0)
          return fail("node " + std::to_string(child) + " has two parents (nodes " + std::to_string(c.parent) + " and " +
                      std::to_string(i) + ")");
        c.parent = static_cast<int>(i);
      }
    // Every node has at most one parent, so a cycle shows up as a walk up
    // the parents that meets itself. Each node is walked once: O(nodes).
    std::vector<int> walkOf(count, -1);  // which walk visited the node, -1 none
    for (int i = 0; i < static_cast<int>(count); ++i) {
      for (int n = i; n >= 0; n = model_.nodes[n].parent) {
        if (walkOf[n] == i) return fail("the node hierarchy has a cycle through node " + std::to_string(n));
        if (walkOf[n] >= 0) break;  // joins an earlier walk, which ended at a root
        walkOf[n] = i;
      }
    }

    int scene = gltf_.defaultScene;
    if (scene >= static_cast<int>(gltf_.scenes.size())) {
      warn("default scene " + std::to_string(scene) + " does not exist; first scene used");
      scene = -1;
    }
    if (scene < 0 && !gltf_.scenes.empty()) scene = 0;
    if (scene >= 0) {
      for (int root : gltf_.scenes[scene].nodes) {
        if (root < 0 || static_cast<size_t>(root) >= count) {
          warn("scene " + std::to_string(scene) + " lists node " + std::to_string(root) + ", which does not exist; ignored");
          continue;
        }
        if (model_.nodes[root].parent >= 0) {
          warn("scene " + std::to_string(scene) + " lists node " + std::to_string(root) + ", which has a parent; ignored");
          continue;
        }
        model_.roots.push_back(root);
      }
    } else {
      for (size_t i = 0; i < count; ++i)
        if (model_.nodes[i].parent < 0) model_.roots.push_back(static_cast<int>(i));
    }
    if (model_.roots.empty() && !model_.meshes.empty()) warn("no scene node shows any mesh; nothing would be drawn");
    return {};
  }

  Result<void> loadAnimations() {
    for (size_t a = 0; a < gltf_.animations.size(); ++a) {
      const tinygltf::Animation& src = gltf_.animations[a];
      Animation anim;
      anim.name = src.name.empty() ? "animation_" + std::to_string(a) : src.name;
      for (size_t c = 0; c < src.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = src.channels[c];
        const std::string label = "animation '" + anim.name + "' channel " + std::to_string(c);
        if (ch.target_path != "weights") {
          ++anim.otherChannelCount;
          if (auto ok = readNodeChannel(reader_, src, c, label, model_, anim); !ok) return fail(ok.error());
          continue;
        }
        if (ch.target_node < 0 || static_cast<size_t>(ch.target_node) >= model_.nodes.size() ||
            model_.nodes[ch.target_node].mesh < 0) {
          warn(label + " animates the weights of node " + std::to_string(ch.target_node) + ", which has no mesh; skipped");
          continue;
        }
        if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= src.samplers.size()) {
          warn(label + " uses sampler " + std::to_string(ch.sampler) + ", the animation has " +
               std::to_string(src.samplers.size()) + "; skipped");
          continue;
        }
        const tinygltf::AnimationSampler& sampler = src.samplers[ch.sampler];
        WeightsChannel out;
        out.node = ch.target_node;
        out.mesh = model_.nodes[ch.target_node].mesh;
        out.targetCount = model_.meshes[out.mesh].targetNames.size();
        if (sampler.interpolation == "STEP") out.interpolation = Interpolation::Step;
        else if (sampler.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
        else if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
        else {
          warn(label + " has unknown interpolation '" + sampler.interpolation + "'; LINEAR used");
        }
        auto times = reader_.readScalars(sampler.input, label + " input");
        if (!times) return fail(times.error());
        auto values = reader_.readScalars(sampler.output, label + " output");
        if (!values) return fail(values.error());
        const size_t perKey = out.targetCount * (out.interpolation == Interpolation::CubicSpline ? 3 : 1);
        if (values->size() != times->size() * perKey) {
          warn(label + ": output has " + std::to_string(values->size()) + " values, expected " +
               std::to_string(times->size() * perKey) + " (" + std::to_string(times->size()) + " keys x " +
               std::to_string(perKey) + "); skipped");
          continue;
        }
        if (!std::is_sorted(times->begin(), times->end())) {
          warn(label + ": key times are not increasing; skipped");
          continue;
        }
        out.times = std::move(*times);
        out.values = std::move(*values);
        anim.channels.push_back(std::move(out));
      }
      model_.animations.push_back(std::move(anim));
    }
    return {};
  }

  // KHR_texture_transform of a base colour texture, when it can be baked into
  // TEXCOORD_0 (the engine samples every texture of a material through it).
  std::optional<UvTransform> baseColorUvTransform(const tinygltf::TextureInfo& info, int image, const std::string& where) {
    std::string problem;
    auto t = parseTextureTransform(info, problem);
    if (!problem.empty()) warn(where + ": " + kKhrTextureTransform + " " + problem + "; ignored");
    if (!t || image < 0) return std::nullopt;
    const int set = t->texCoord >= 0 ? t->texCoord : info.texCoord;
    if (set != 0) {
      warn(where + ": " + kKhrTextureTransform + " on TEXCOORD_" + std::to_string(set) + ", only TEXCOORD_0 is read; ignored");
      return std::nullopt;
    }
    outcomes_[kKhrTextureTransform] = "applied: baked into TEXCOORD_0 for " + std::to_string(++uvTransformed_) +
                                      " material(s)' base colour";
    return t;
  }

  std::string file_;
  const tinygltf::Model& gltf_;
  const GltfLoadLimits& limits_;
  const GltfFileAccess& files_;
  ExtensionOutcomes& outcomes_;
  GltfAccessorReader reader_;
  Model model_;
  std::vector<int> imageRemap_;  // glTF image -> Model::images index, -1 when skipped
  std::vector<std::optional<UvTransform>> uvTransforms_;  // per material
  int ktx2Skipped_ = 0, webpDecoded_ = 0, uvTransformed_ = 0;
};

enum class Container { Json, Glb };

// Meshopt views and Draco primitives become plain buffer data before the
// model is built, so everything after reads ordinary accessors.
Result<void> decodeCompressedGeometry(tinygltf::Model& gltf, const std::vector<MeshoptPlaceholder>& placeholders,
                                      const GltfLoadLimits& limits, ExtensionOutcomes& outcomes) {
  auto meshopt = decodeMeshoptViews(gltf, placeholders, limits.maxDecodedBytes);
  if (!meshopt) return meshopt.error();
  const std::string views = "decoded: " + std::to_string(meshopt->views) + " buffer view(s) (meshoptimizer)";
  if (meshopt->usedExt) outcomes[kExtMeshopt] = views;
  if (meshopt->usedKhr) outcomes[kKhrMeshopt] = views;
  auto draco = decodeDracoPrimitives(gltf, limits.maxDecodedBytes);
  if (!draco) return draco.error();
  if (*draco > 0) outcomes[kKhrDraco] = "decoded: " + std::to_string(*draco) + " primitive(s) (Draco)";
  return {};
}

Result<Container> detectContainer(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  if (hasGlbMagic(bytes)) return Container::Glb;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".glb") {
    auto glb = parseGlb(bytes);  // names the wrong magic or the truncation
    return glb.error();
  }
  size_t i = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;  // UTF-8 BOM
  while (i < bytes.size() && std::isspace(bytes[i])) ++i;
  if (i < bytes.size() && bytes[i] == '{') return Container::Json;
  if (bytes.empty()) return makeError(ErrorKind::Malformed, "file is empty");
  return makeError(ErrorKind::Malformed, "neither glTF JSON nor a GLB (no '{' and no 'glTF' magic at the start)");
}

}  // namespace

Result<Model> loadModel(const std::filesystem::path& path) { return loadModel(path, GltfLoadLimits{}); }

Result<Model> loadModel(const std::filesystem::path& path, const GltfLoadLimits& limits) {
  const std::string file = path.string();
  try {
    auto bytes = readFileBytes(path, limits.maxFileBytes);
    if (!bytes) return bytes.error();
    auto container = detectContainer(*bytes, path);
    if (!container) return container.error().prefixed(file + ": ");
    // The pre-pass (nlohmann) and tinygltf parse recursively: a hostile nesting depth is refused before either.
    std::span<const uint8_t> jsonText = *bytes;
    if (*container == Container::Glb) {
      auto glb = parseGlb(*bytes);
      if (!glb) return glb.error().prefixed(file + ": ");
      jsonText = glb->json;
    }
    if (auto nesting = checkJsonNesting({reinterpret_cast<const char*>(jsonText.data()), jsonText.size()}, file); !nesting)
      return nesting.error();
    // Compressed files hold what tinygltf refuses (buffers without data, indices without a bufferView).
    std::vector<uint8_t> stubbed;
    auto placeholders = prepareCompressedGltf(*bytes, *container == Container::Glb, stubbed);
    if (!placeholders) return placeholders.error().prefixed(file + ": ");
    if (!stubbed.empty()) *bytes = std::move(stubbed);

    std::error_code ec;
    const std::filesystem::path baseDir = std::filesystem::absolute(path, ec).parent_path();
    GltfFileAccess files(baseDir, limits.maxFileBytes);
    tinygltf::Model gltf;
    ImageHookContext imageHook{&gltf};
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(files.callbacks());
    parser.SetImageLoader(&keepEncodedImage, &imageHook);

    std::string err, warn;
    bool parsed = false;
    if (*container == Container::Glb) {
      auto glb = parseGlb(*bytes);
      if (!glb) return glb.error().prefixed(file + ": ");
      parsed = parser.LoadBinaryFromMemory(&gltf, &err, &warn, bytes->data(), static_cast<unsigned>(bytes->size()),
                                           files.baseDirString());
    } else {
      parsed = parser.LoadASCIIFromString(&gltf, &err, &warn, reinterpret_cast<const char*>(bytes->data()),
                                          static_cast<unsigned>(bytes->size()), files.baseDirString());
    }
    if (!parsed) {
      // What our file access refused or could not find says more than tinygltf's summary.
      if (!files.problems().empty()) return makeError(ErrorKind::Malformed, file + ": " + files.problems().front());
      return makeError(ErrorKind::Malformed, file + ": " + (err.empty() ? std::string("glTF parse failed") : oneLine(err)));
    }
    if (auto problem = assetVersionProblem(gltf.asset)) return problem->prefixed(file + ": ");
    ExtensionOutcomes outcomes;
    if (auto ok = decodeCompressedGeometry(gltf, *placeholders, limits, outcomes); !ok)
      return ok.error().prefixed(file + ": ");
    ModelBuilder builder(file, gltf, limits, files, outcomes);
    auto model = builder.build();
    if (!model) return model;
    model->extensions = describeExtensions(gltf, outcomes);
    for (std::string& line : splitLines(warn))
      if (line.find("Failed to load external") == std::string::npos && line.find("File not found") == std::string::npos)
        model->warnings.push_back("tinygltf: " + line);
    return model;
  } catch (const std::bad_alloc&) {
    return makeError(ErrorKind::TooLarge, file + ": out of memory while loading");
  } catch (const std::exception& e) {
    return makeError(ErrorKind::Malformed, file + ": " + e.what());
  }
}

}  // namespace eng
