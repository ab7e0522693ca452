// glTF images, textures and materials into Model::images / Model::materials.
#include "engine/scene/gltf_model_builder.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "engine/scene/gltf_mtoon.h"
#include "engine/scene/gltf_sampler.h"
#include "engine/scene/image_io.h"

namespace eng {
namespace {

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

}  // namespace

std::string GltfModelBuilder::imageLabel(size_t i) const {
  const tinygltf::Image& src = gltf_.images[i];
  return src.uri.empty() || isDataUri(src.uri) ? (src.name.empty() ? "embedded" : src.name) : src.uri;
}

// Images are checked here and decoded when a material first draws them
// (decodedImage): one no material uses is never decoded.
Result<void> GltfModelBuilder::loadImages() {
  imageRemap_.assign(gltf_.images.size(), kImageSkipped);
  for (size_t i = 0; i < gltf_.images.size(); ++i) {
    const tinygltf::Image& src = gltf_.images[i];
    const std::string label = imageLabel(i);
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
    imageRemap_[i] = kImagePending;
  }
  return {};
}

// Images with the same encoded bytes (one bufferView or file named by many
// images) share one decode; the pixels are charged to the budget first.
int GltfModelBuilder::decodedImage(size_t i) {
  int& slot = imageRemap_[i];
  if (slot != kImagePending) return slot;
  slot = kImageSkipped;
  const tinygltf::Image& src = gltf_.images[i];
  const auto [same, fresh] =
      imagesByBytes_.try_emplace(std::string_view(reinterpret_cast<const char*>(src.image.data()), src.image.size()), -1);
  if (!fresh) return slot = same->second;
  const std::string label = imageLabel(i);
  auto size = imageSize(src.image, label, limits_.maxImagePixels);
  if (size) {
    auto ok = budget_.charge(static_cast<size_t>(size->width) * static_cast<size_t>(size->height), 4,
                             "image " + std::to_string(i) + " ('" + label + "', " + std::to_string(size->width) + "x" +
                                 std::to_string(size->height) + ") decoded");
    if (!ok) {
      if (!overBudget_) overBudget_ = fail(ok.error());
      return kImageSkipped;
    }
  }
  auto decoded = size ? decodeImage(src.image, label, limits_.maxImagePixels) : Result<Image>(size.error());
  if (!decoded) {
    warn("image " + std::to_string(i) + " skipped: " + decoded.error().message);
    return kImageSkipped;
  }
  if (isWebp(src.image))
    outcomes_[kExtTextureWebp] = "decoded: " + std::to_string(++webpDecoded_) + " WebP image(s) (libwebp)";
  same->second = slot = static_cast<int>(model_.images.size());
  model_.images.push_back(std::move(*decoded));
  return slot;
}

int GltfModelBuilder::imageOfTexture(int texture, const std::string& where) {
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
  return decodedImage(static_cast<size_t>(source));
}

int GltfModelBuilder::modelImage(int gltfImage, const std::string& where) {
  if (gltfImage < 0 || static_cast<size_t>(gltfImage) >= imageRemap_.size()) {
    warn(where + " refers to image " + std::to_string(gltfImage) + ", the file has " +
         std::to_string(imageRemap_.size()) + "; ignored");
    return -1;
  }
  return decodedImage(static_cast<size_t>(gltfImage));
}

void GltfModelBuilder::readToonShading(size_t index, Material& mat, const std::string& where) {
  MtoonRead mtoon = readMtoon(gltf_, index);
  for (std::string& problem : mtoon.problems) warn(std::move(problem));
  if (!mtoon.toon) return;
  mat.toon = mtoon.toon;
  const auto& [metalRough, normal, occlusion, emissive, matcap, shadingShift, rimMultiply, outlineWidth] =
      kMaterialTextures;
  // A VRM 0.x material keeps its normal map among MToon's textures (the
  // glTF material is a fallback for viewers without VRM); a normalTexture of
  // the glTF material's own is drawn instead where it has one.
  if (mtoon.normalTexture >= 0 && gltf_.materials[index].normalTexture.index < 0) {
    readMaterialTexture(normal, mtoon.normalTexture, 0, {}, baseColorUvs_.back(), mat, where + " (VRM 0.x _BumpMap)");
    mat.normalScale = mtoon.normalScale;
  }
  // The matcap is looked up by the normal, so no UV set of its own matters.
  if (mtoon.matcapTexture >= 0) {
    mat.matcapImage = imageOfTexture(mtoon.matcapTexture, where + " MToon matcap");
    if (mat.matcapImage >= 0) mat.matcapSampling = textureSampling(mtoon.matcapTexture, where);
  }
  for (const auto& [slot, texture] : {std::pair{&shadingShift, &mtoon.shadingShiftTexture},
                                      std::pair{&rimMultiply, &mtoon.rimMultiplyTexture},
                                      std::pair{&outlineWidth, &mtoon.outlineWidthTexture}})
    readMaterialTexture(*slot, texture->index, texture->texCoord, texture->extensions, baseColorUvs_.back(), mat,
                        where + " MToon");
  const int baseTexture = gltf_.materials[index].pbrMetallicRoughness.baseColorTexture.index;
  if (mat.toon->shadeFromBaseTexture) {
    // The shade is drawn through the base colour's texture: exact when both
    // name the same image (VRoid's exports), an approximation otherwise.
    auto sourceOf = [&](int texture) {
      return texture >= 0 && size_t(texture) < gltf_.textures.size() ? gltf_.textures[size_t(texture)].source : -1;
    };
    if (mat.baseColorImage < 0) {
      warn(where + ": its MToon shade texture is not drawn (the material has no base colour texture to draw it with)");
      mat.toon->shadeFromBaseTexture = false;
    } else if (sourceOf(mtoon.shadeTexture) != sourceOf(baseTexture)) {
      warn(where + ": its MToon shade texture (texture " + std::to_string(mtoon.shadeTexture) +
           ") is drawn with the base colour's texture (texture " + std::to_string(baseTexture) + ")");
    }
  }
  outcomes_[kVrmcMaterialsMtoon] = "applied: " + std::to_string(++toonMaterials_) +
                                   " material(s) toon-shaded (shade colour, shading shift and toony, GI "
                                   "equalization, parametric rim, matcap, outline, their masks)";
}

void GltfModelBuilder::readAlphaMode(const tinygltf::Material& src, Material& mat, const std::string& where) {
  if (src.alphaMode == "MASK") {
    mat.alphaMode = AlphaMode::Mask;
    mat.alphaCutoff = static_cast<float>(src.alphaCutoff);
    if (!std::isfinite(mat.alphaCutoff) || mat.alphaCutoff < 0.0f) {
      warn(where + " has alphaCutoff " + std::to_string(src.alphaCutoff) + ", not a number >= 0; 0.5 used");
      mat.alphaCutoff = 0.5f;
    }
  } else if (src.alphaMode == "BLEND") {
    mat.alphaMode = AlphaMode::Blend;
  } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
    warn(where + " has alphaMode '" + src.alphaMode + "' (glTF knows OPAQUE, MASK, BLEND); drawn opaque");
  }
}

// Factors that are not finite fall back to glTF's defaults together, so a
// broken material draws plain rather than half of it broken.
void GltfModelBuilder::readFactorsAndEmission(const tinygltf::Material& src, const BaseColorUv& uvs, Material& mat,
                                              const std::string& where) {
  if (src.emissiveFactor.size() == 3)
    mat.emissiveFactor = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
  if (!std::isfinite(mat.roughness) || !std::isfinite(mat.metallic) || !std::isfinite(mat.normalScale) ||
      !std::isfinite(mat.occlusionStrength) || glm::any(glm::isnan(mat.baseColorFactor)) || glm::any(glm::isinf(mat.baseColorFactor)) ||
      glm::any(glm::isnan(mat.emissiveFactor)) || glm::any(glm::isinf(mat.emissiveFactor))) {
    warn(where + " has non-finite factors; defaults used");
    mat.baseColorFactor = glm::vec4(1.0f);
    mat.emissiveFactor = glm::vec3(0.0f);
    mat.roughness = 1.0f;
    mat.metallic = 1.0f;
    mat.normalScale = 1.0f;
    mat.occlusionStrength = 1.0f;
  }
  // The emissive texture masks the factor: without it (left out, or not
  // decodable) the factor would light the whole surface, so it goes too.
  if (mat.emissiveFactor != glm::vec3(0.0f)) {
    const auto& [metalRough, normal, occlusion, emissive, matcap, shadingShift, rimMultiply, outlineWidth] =
        kMaterialTextures;
    readMaterialTexture(emissive, src.emissiveTexture.index, src.emissiveTexture.texCoord,
                        src.emissiveTexture.extensions, uvs, mat, where);
    const bool drawn = mat.emissiveImage >= 0 && !model_.images[static_cast<size_t>(mat.emissiveImage)].rgba8.empty();
    if (src.emissiveTexture.index >= 0 && !drawn) {
      warn(where + ": its emissiveFactor is left out with its emissiveTexture");
      mat.emissiveFactor = glm::vec3(0.0f);
      mat.emissiveImage = -1;
    }
  }
}

// A layer drawn over the base colour as a target's weight rises (the made
// wrinkles of facial autorig): extras.detailLayers = [{image, target, strength, blend}].
void GltfModelBuilder::readDetailLayers(const tinygltf::Material& src, Material& mat, const std::string& where) {
  if (!src.extras.IsObject() || !src.extras.Has("detailLayers")) return;
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
    if (layer.Has("blend")) {
      const tinygltf::Value& blend = layer.Get("blend");
      if (blend.IsString() && blend.Get<std::string>() == "modulate") {
        d.blend = DetailBlend::Modulate;
      } else if (!blend.IsString() || blend.Get<std::string>() != "mix") {
        warn(lw + " has blend " + (blend.IsString() ? "'" + blend.Get<std::string>() + "'" : std::string("that is not a string")) +
             " (known: 'mix', 'modulate'); ignored");
        continue;
      }
    }
    mat.detailLayers.push_back(std::move(d));
  }
}

void GltfModelBuilder::loadMaterials() {
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
    baseColorUvs_.push_back(baseColorUv(pbr.baseColorTexture, mat.baseColorImage, where));
    if (mat.baseColorImage >= 0) mat.baseColorSampling = textureSampling(pbr.baseColorTexture.index, where);
    mat.roughness = static_cast<float>(pbr.roughnessFactor);
    mat.metallic = static_cast<float>(pbr.metallicFactor);
    const BaseColorUv& uvs = baseColorUvs_.back();
    const auto& [metalRough, normal, occlusion, emissive, matcap, shadingShift, rimMultiply, outlineWidth] =
        kMaterialTextures;
    readMaterialTexture(metalRough, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, uvs, mat, where);
    readMaterialTexture(normal, src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions, uvs, mat,
                    where);
    readMaterialTexture(occlusion, src.occlusionTexture.index, src.occlusionTexture.texCoord, src.occlusionTexture.extensions,
                    uvs, mat, where);
    mat.normalScale = static_cast<float>(src.normalTexture.scale);
    mat.occlusionStrength = std::clamp(static_cast<float>(src.occlusionTexture.strength), 0.0f, 1.0f);  // NaN stays NaN
    mat.doubleSided = src.doubleSided;
    if (src.extensions.count(kKhrMaterialsUnlit)) {
      mat.unlit = true;
      outcomes_[kKhrMaterialsUnlit] = "applied: " + std::to_string(++unlitMaterials_) + " material(s) drawn unlit";
    }
    readToonShading(i, mat, where);
    readAlphaMode(src, mat, where);
    readFactorsAndEmission(src, uvs, mat, where);
    readDetailLayers(src, mat, where);
    model_.materials.push_back(std::move(mat));
  }
}

// Data textures are drawn through the primitive's one UV set, the base
// colour's: a texture on another set, or moved by another transform, would
// put the metal, the bumps or the shade in the wrong places, so it is left out.
void GltfModelBuilder::readMaterialTexture(const MaterialTexture& slot, int texture, int texCoord,
                                       const tinygltf::ExtensionMap& extensions, const BaseColorUv& base, Material& mat,
                                       const std::string& where) {
  if (texture < 0) return;
  std::string problem;
  const std::optional<UvTransform> transform = parseTextureTransform(extensions, problem);
  const int set = transform && transform->texCoord >= 0 ? transform->texCoord : std::max(texCoord, 0);
  auto same = [](const std::optional<UvTransform>& a, const std::optional<UvTransform>& b) {
    if (!a || !b) return !a && !b;
    return a->offset == b->offset && a->rotation == b->rotation && a->scale == b->scale;
  };
  if (!problem.empty() || set != base.set || !same(transform, base.transform)) {
    warn(where + ": its " + slot.name + " reads TEXCOORD_" + std::to_string(set) +
         (transform ? " through a texture transform" : "") + ", unlike its base colour (TEXCOORD_" + std::to_string(base.set) +
         (base.transform ? " through a texture transform" : "") + "); it is not drawn");
    return;
  }
  mat.*slot.image = imageOfTexture(texture, where);
  if (mat.*slot.image >= 0) mat.*slot.sampling = textureSampling(texture, where);
}

GltfModelBuilder::BaseColorUv GltfModelBuilder::baseColorUv(const tinygltf::TextureInfo& info, int image,
                                                            const std::string& where) {
  BaseColorUv uv;
  std::string problem;
  uv.transform = parseTextureTransform(info.extensions, problem);
  if (!problem.empty()) warn(where + ": " + kKhrTextureTransform + " " + problem + "; ignored");
  if (image < 0) return {};
  uv.set = uv.transform && uv.transform->texCoord >= 0 ? uv.transform->texCoord : std::max(info.texCoord, 0);
  if (uv.transform)
    outcomes_[kKhrTextureTransform] = "applied: baked into the UV set of " + std::to_string(++uvTransformed_) +
                                      " material(s)' base colour";
  return uv;
}

TextureSampling GltfModelBuilder::textureSampling(int texture, const std::string& where) {
  const int sampler = gltf_.textures[static_cast<size_t>(texture)].sampler;
  if (sampler < 0) return {};
  if (static_cast<size_t>(sampler) >= gltf_.samplers.size()) {
    warn(where + ": texture " + std::to_string(texture) + " refers to sampler " + std::to_string(sampler) +
         ", the file has " + std::to_string(gltf_.samplers.size()) + "; the default sampling used");
    return {};
  }
  const tinygltf::Sampler& src = gltf_.samplers[static_cast<size_t>(sampler)];
  std::string problem;
  TextureSampling sampling = samplingFromGltf({src.magFilter, src.minFilter, src.wrapS, src.wrapT}, problem);
  if (!problem.empty())
    warn(where + ": sampler " + std::to_string(sampler) + " has " + problem +
         ", which glTF does not define; the default used there");
  return sampling;
}

}  // namespace eng
