#include "engine/vk/draw/gpu_model.h"

#include <atomic>

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <span>
#include <string>

#include "engine/vk/device/descriptor_write.h"
#include "engine/core/log.h"
#include "engine/scene/inner_face_parts.h"
#include "engine/scene/mesh_lod.h"
#include "engine/scene/model_check.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/weights.h"
#include "engine/vk/draw/detail_array.h"
#include "engine/vk/draw/sparse_deltas.h"
#include "engine/view/scene_mesh_nodes.h"
#include "engine/vk/draw/texture.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

// Used by primitives with material -1: a light neutral clay.
Material defaultMaterial() {
  Material m;
  m.name = "default";
  m.baseColorFactor = glm::vec4(0.80f, 0.78f, 0.76f, 1.0f);
  m.roughness = 0.6f;
  m.metallic = 0.0f;
  return m;
}

}  // namespace

// Appends byte ranges at aligned offsets; the result becomes one buffer.
// Outside the anonymous namespace: GpuModelStaging (declared in the header)
// holds these, and a type with linkage must not hold a file-local one.
class ByteBlob {
 public:
  VkDeviceSize append(const void* data, size_t size, VkDeviceSize alignment) {
    VkDeviceSize offset = alignUp(alignment);
    bytes_.resize(offset + size);
    if (data) std::memcpy(bytes_.data() + offset, data, size);  // else stays zero
    return offset;
  }
  template <class T>
  VkDeviceSize append(std::span<const T> items, VkDeviceSize alignment) {
    return append(items.data(), items.size_bytes(), alignment);
  }
  std::span<std::byte> range(VkDeviceSize offset, size_t size) { return {bytes_.data() + offset, size}; }
  const std::vector<std::byte>& bytes() const { return bytes_; }
  bool empty() const { return bytes_.empty(); }

 private:
  VkDeviceSize alignUp(VkDeviceSize alignment) {
    VkDeviceSize offset = (bytes_.size() + alignment - 1) / alignment * alignment;
    bytes_.resize(offset);
    return offset;
  }
  std::vector<std::byte> bytes_;
};

namespace {

std::string where(const Model& model, size_t mesh, size_t primitive) {
  std::string file = model.sourcePath.empty() ? std::string("<model>") : model.sourcePath;
  return file + ": mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

// Target indices travel as float values, exact up to 2^24.
constexpr size_t kMaxSparseTargets = size_t{1} << 24;

}  // namespace

namespace {

// Whether the material's primitives are also drawn as an MToon outline (a
// blended surface has no depth to hide the hull's inside behind).
bool hasOutline(const Material& mat) {
  return mat.toon && mat.toon->outlineMode != ToonShading::OutlineWidth::None && mat.toon->outlineWidth > 0.0f &&
         mat.alphaMode != AlphaMode::Blend;
}

// The material's factors and the draw flags the shaders branch on.
void setMaterialConstants(DrawConstants& constants, const Material& mat, const SparseDeltas& sparse) {
  constants.roughness = mat.roughness;
  constants.metallic = mat.metallic;
  constants.detailLayerCount = static_cast<uint32_t>(mat.detailLayers.size());
  constants.flags = (sparse.hasNormals ? kDrawFlagNormalDeltas : 0u) |
                    (sparse.hasTangents ? kDrawFlagTangentDeltas : 0u) |
                    (mat.doubleSided ? kDrawFlagDoubleSided : 0u) |
                    (sparse.hasCreases ? kDrawFlagCreases : 0u) |
                    (sparse.entries.empty() ? 0u : kDrawFlagMorphed) |
                    (mat.alphaMode == AlphaMode::Mask ? kDrawFlagAlphaMask : 0u) |
                    (mat.alphaMode == AlphaMode::Blend ? kDrawFlagAlphaBlend : 0u) |
                    (mat.unlit && !mat.toon ? kDrawFlagUnlit : 0u) |
                    (mat.toon ? kDrawFlagToon : 0u) |
                    (mat.toon && mat.toon->shadeFromBaseTexture ? kDrawFlagToonShadeTexture : 0u) |
                    (hasOutline(mat) ? kDrawFlagToonOutline : 0u) |
                    (mat.normalImage >= 0 ? kDrawFlagNormalMap : 0u) |
                    (mat.emissiveImage >= 0 ? kDrawFlagEmissiveTexture : 0u) |
                    (mat.toon && mat.matcapImage >= 0 ? kDrawFlagToonMatcap : 0u) |
                    (mat.toon && mat.shadingShiftImage >= 0 ? kDrawFlagToonShadingShiftTexture : 0u) |
                    (mat.toon && mat.rimMultiplyImage >= 0 ? kDrawFlagToonRimMultiply : 0u) |
                    (hasOutline(mat) && mat.outlineWidthImage >= 0 ? kDrawFlagToonOutlineWidthTexture : 0u);
  if (mat.toon) constants.toonShadingShiftScale = mat.toon->shadingShiftTextureScale;
  constants.alphaCutoff = mat.alphaCutoff;
  constants.normalScale = mat.normalScale;
  constants.occlusionStrength = mat.occlusionImage >= 0 ? mat.occlusionStrength : 0.0f;
}

// Runs by detail layer for an opaque primitive with layers (a blended one
// keeps its triangles' order).
std::optional<DetailRegions> detailRegionsOf(const Model& model, const Material* material) {
  if (!material || material->detailLayers.empty() || material->alphaMode == AlphaMode::Blend) return std::nullopt;
  std::vector<const Image*> layerImages;
  for (const DetailLayer& layer : material->detailLayers)
    layerImages.push_back(layer.image >= 0 && size_t(layer.image) < model.images.size() ? &model.images[size_t(layer.image)]
                                                                                         : nullptr);
  return DetailRegions(layerImages);
}

}  // namespace

InstanceMaterial instanceMaterial(const Material& mat) {
  InstanceMaterial out;
  out.baseColorFactor = mat.baseColorFactor;
  out.emissive = glm::vec4(mat.emissiveFactor, 0.0f);
  if (const std::optional<ToonShading>& t = mat.toon) {
    out.toonShade = glm::vec4(t->shadeColor, t->rimLift);
    out.toonShading = glm::vec4(t->shadingShift, t->shadingToony, t->giEqualization, t->rimLightingMix);
    out.toonRim = glm::vec4(t->rimColor, t->rimFresnelPower);
    out.toonOutline = glm::vec4(t->outlineColor, t->outlineWidth);
    const float mode = t->outlineMode == ToonShading::OutlineWidth::World    ? 1.0f
                       : t->outlineMode == ToonShading::OutlineWidth::Screen ? 2.0f
                                                                             : 0.0f;
    out.toonOutlineStyle = glm::vec4(mode, t->outlineLightingMix, 0.0f, 0.0f);
    out.toonMatcap = glm::vec4(t->matcapFactor, 0.0f);
  }
  return out;
}

// Byte ranges of one primitive's data in the staging blobs (declared in gpu_model.h).
struct PrimitiveRanges {
  VkDeviceSize morphOffsets = 0, morphOffsetsSize = 0;  // size 0: no deltas
  VkDeviceSize morphEntries = 0, morphEntriesSize = 0;
  VkDeviceSize rest = 0, restSize = 0;  // rest position .. tangent arrays in the vertex buffer
  VkDeviceSize detail = 0;
  VkDeviceSize skin = 0;
};

namespace {


// Vertex and index arrays of one primitive. The position array starts at a
// storage-buffer offset: the morph pre-pass reads position .. tangent as one
// storage range (DrawConstants::rest* are float offsets into it).
GpuPrimitive appendGeometry(ByteBlob& vertices, ByteBlob& indices, const Primitive& prim, const Image* baseColour,
                            const DetailRegions* regions, bool levelsOfDetail, VkDeviceSize storageAlign,
                            PrimitiveRanges& ranges) {
  const size_t n = prim.vertexCount();
  GpuPrimitive gp;
  gp.vertexCount = static_cast<uint32_t>(n);
  gp.indexCount = static_cast<uint32_t>(prim.indices.size());
  Aabb box;
  for (const glm::vec3& p : prim.positions) box.extend(p);
  gp.centre = box.valid() ? box.center() : glm::vec3(0.0f);
  gp.positionOffset = vertices.append(std::span(prim.positions), storageAlign);
  gp.normalOffset = vertices.append(std::span(prim.normals), 16);
  gp.texcoordOffset = prim.texcoords.empty() ? vertices.append(nullptr, n * sizeof(glm::vec2), 16)
                                             : vertices.append(std::span(prim.texcoords), 16);
  gp.tangentOffset = prim.tangents.empty() ? vertices.append(nullptr, n * sizeof(glm::vec4), 16)
                                           : vertices.append(std::span(prim.tangents), 16);
  ranges.rest = gp.positionOffset;
  ranges.restSize = gp.tangentOffset + n * sizeof(glm::vec4) - gp.positionOffset;
  gp.constants.restPosition = 0;
  gp.constants.restNormal = static_cast<uint32_t>((gp.normalOffset - gp.positionOffset) / sizeof(float));
  gp.constants.restTangent = static_cast<uint32_t>((gp.tangentOffset - gp.positionOffset) / sizeof(float));
  if (prim.colors.size() == n) {
    gp.colorOffset = vertices.append(std::span(prim.colors), 16);
  } else {
    const std::vector<glm::vec4> white(n, glm::vec4(1.0f));
    gp.colorOffset = vertices.append(std::span(white), 16);
  }
  // Each level's list in runs by the detail layers that can show (when the primitive has any).
  const auto appendLevel = [&](std::span<const uint32_t> list, std::vector<DetailRuns::Run>& runs) {
    if (!regions) return indices.append(list, 16);
    DetailRuns ordered = regions->runsOf(list, prim.texcoords);
    runs = std::move(ordered.runs);
    return indices.append(std::span<const uint32_t>(ordered.indices), 16);
  };
  gp.indexOffset = appendLevel(prim.indices, gp.detailRuns);
  if (!levelsOfDetail) return gp;
  const std::vector<uint8_t> kept = keptTriangles(prim, baseColour);
  for (const LodLevel& level : buildLodChain(prim.positions, prim.indices, {}, kept)) {
    GpuLod& lod = gp.lods.emplace_back();
    lod.indexOffset = appendLevel(level.indices, lod.detailRuns);
    lod.indexCount = static_cast<uint32_t>(level.indices.size());
    lod.error = level.error;
  }
  return gp;
}

// Joint influences as skin.glsl reads them: per vertex and group of four,
// the joint indices then the weights' float bits (two uvec4).
VkDeviceSize appendInfluences(ByteBlob& blob, const Primitive& prim, VkDeviceSize alignment) {
  std::vector<glm::uvec4> packed(prim.joints.size() * 2);
  for (size_t i = 0; i < prim.joints.size(); ++i) {
    packed[2 * i] = glm::uvec4(prim.joints[i]);
    std::memcpy(&packed[2 * i + 1], &prim.jointWeights[i], sizeof(glm::vec4));
  }
  return blob.append(std::span<const glm::uvec4>(packed), alignment);
}

// The detail layers of a primitive's material, by target index among the
// mesh's targets (UINT32_MAX never matches an active target, so a missing
// target reads as weight 0).
std::vector<GpuDetailLayer> detailLayers(const Model& model, size_t m, size_t p, const Material& mat) {
  const Mesh& mesh = model.meshes[m];
  std::vector<GpuDetailLayer> layers;
  std::string missing;  // one warning for them all: a face stripped of its targets misses every one
  size_t missingCount = 0;
  for (const DetailLayer& layer : mat.detailLayers) {
    auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), layer.target);
    if (it == mesh.targetNames.end())
      missing += (missingCount++ ? ", '" : "'") + layer.target + "'";
    layers.push_back({it == mesh.targetNames.end() ? UINT32_MAX
                                                   : static_cast<uint32_t>(it - mesh.targetNames.begin()),
                      layer.strength, layer.blend == DetailBlend::Modulate ? 1u : 0u});
  }
  if (missingCount == 1)
    logWarning(where(model, m, p) + ": detail layer target " + missing +
               " is not a morph target of this mesh; the layer stays hidden");
  else if (missingCount > 1)
    logWarning(where(model, m, p) + ": detail layer targets " + missing + " are not morph targets of this mesh (" +
               std::to_string(missingCount) + " of " + std::to_string(mat.detailLayers.size()) +
               "); those layers stay hidden");
  return layers;
}

VkDescriptorBufferInfo rangeOr(VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, VkBuffer placeholder) {
  return size > 0 ? VkDescriptorBufferInfo{buffer, offset, size} : VkDescriptorBufferInfo{placeholder, 0, VK_WHOLE_SIZE};
}

}  // namespace

// The device buffers' bytes.
struct GpuModelStaging::Blobs {
  ByteBlob vertices, indices, deltas, detail, skin;
};

GpuModelStaging::GpuModelStaging() : blobs_(std::make_unique<Blobs>()) {}
GpuModelStaging::GpuModelStaging(GpuModelStaging&&) noexcept = default;
GpuModelStaging& GpuModelStaging::operator=(GpuModelStaging&&) noexcept = default;
GpuModelStaging::~GpuModelStaging() = default;

namespace {

std::string modelName(const Model& model) {
  return model.sourcePath.empty() ? std::string("<model>") : model.sourcePath;
}

VkDeviceSize storageAlignment(const VkPhysicalDeviceLimits& limits) {
  return std::max<VkDeviceSize>(
      {limits.minStorageBufferOffsetAlignment, limits.minTexelBufferOffsetAlignment, VkDeviceSize{16}});
}

}  // namespace

Result<void> GpuModelStaging::fits(const VkPhysicalDeviceLimits& limits) const {
  const VkDeviceSize align = storageAlignment(limits);
  if (storageAlign_ % align != 0)
    return makeError(ErrorKind::InvalidArgument, "staged with buffer offsets aligned to " + std::to_string(storageAlign_) +
                                                     " bytes, the device needs " + std::to_string(align));
  if (largestTexelBuffer_ > limits.maxTexelBufferElements)
    return makeError(ErrorKind::TooLarge, "staged texel buffers of " + std::to_string(largestTexelBuffer_) +
                                              " elements, the device allows " +
                                              std::to_string(limits.maxTexelBufferElements));
  return {};
}

Result<GpuModel> GpuModel::create(const Context& ctx, const SceneLayouts& layouts, const Model& model) {
  auto staging = GpuModelStaging::build(model, ctx.deviceInfo().properties.limits);
  if (!staging) return staging.error();
  return create(ctx, layouts, model, *staging);
}

Result<GpuModel> GpuModel::create(const Context& ctx, const SceneLayouts& layouts, const Model& model,
                                  const GpuModelStaging& staging) {
  if (auto fits = staging.fits(ctx.deviceInfo().properties.limits); !fits)
    return fits.error().prefixed(modelName(model) + ": ");
  if (staging.meshes_.size() != model.meshes.size())
    return makeError(ErrorKind::InvalidArgument, modelName(model) + ": staged with " +
                                                     std::to_string(staging.meshes_.size()) + " meshes, the model has " +
                                                     std::to_string(model.meshes.size()));
  GpuModel gpu;
  static std::atomic<uint64_t> uploads{0};
  gpu.uploadSerial_ = ++uploads;
  gpu.name_ = modelName(model);
  gpu.bounds_ = model.skins.empty() ? model.bounds() : posedBounds(model, restPose(model));
  gpu.weightCount_ = WeightLayout(model).total();
  gpu.materialCount_ = static_cast<uint32_t>(model.materials.size());
  for (const Material& mat : model.materials) gpu.materials_.push_back(instanceMaterial(mat));
  gpu.materials_.push_back(instanceMaterial(defaultMaterial()));
  gpu.meshNodes_ = sceneMeshNodes(model);
  gpu.skins_ = model.skins;
  poseWorldMatrices(model, restPose(model), gpu.restWorld_);

  gpu.meshes_ = staging.meshes_;
  ENG_TRY(gpu.uploadBuffers(ctx, staging));
  ENG_TRY(gpu.uploadTextures(ctx, model));
  ENG_TRY(gpu.createDescriptorSets(ctx, layouts, model, staging));
  return gpu;
}

// Lays every primitive's geometry, sparse deltas, detail-layer parameters and
// joint influences out in the staging blobs, with the meshes' draw records.
Result<GpuModelStaging> GpuModelStaging::build(const Model& model, const VkPhysicalDeviceLimits& limits) {
  if (auto valid = checkModel(model, ModelCheck::gpuUpload()); !valid) return valid.error().prefixed(modelName(model) + ": ");
  GpuModelStaging out;
  Blobs& staging = *out.blobs_;
  const VkDeviceSize storageAlign = storageAlignment(limits);
  out.storageAlign_ = storageAlign;
  const WeightLayout weightLayout(model);
  const Material fallback = defaultMaterial();
  const std::vector<std::vector<bool>> insideTheHead = partsInsideTheHead(model);
  out.meshes_.resize(model.meshes.size());
  out.ranges_.resize(model.meshes.size());
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    GpuMesh& gm = out.meshes_[m];
    gm.name = mesh.name;
    gm.targetCount = static_cast<uint32_t>(mesh.targetNames.size());
    gm.weightOffset = weightLayout.offset(static_cast<int>(m));
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      PrimitiveRanges& ranges = out.ranges_[m].emplace_back();
      const Material* material =
          prim.material >= 0 && size_t(prim.material) < model.materials.size() ? &model.materials[size_t(prim.material)] : nullptr;
      const Image* baseColour = material && material->baseColorImage >= 0 && size_t(material->baseColorImage) < model.images.size()
                                    ? &model.images[size_t(material->baseColorImage)]
                                    : nullptr;
      const std::optional<DetailRegions> regions = detailRegionsOf(model, material);
      // No coarser levels inside the head: a simplified eyeball moves the
      // catchlight on its cornea (the normals), which the simplifier cannot see.
      GpuPrimitive gp = appendGeometry(staging.vertices, staging.indices, prim, baseColour, regions ? &*regions : nullptr,
                                       !insideTheHead[m][p], storageAlign, ranges);

      if (prim.targets.size() > kMaxSparseTargets)
        return makeError(ErrorKind::TooLarge, where(model, m, p) + ": " + std::to_string(prim.targets.size()) +
                         " morph targets, more than the " + std::to_string(kMaxSparseTargets) +
                         " a sparse delta entry can name");
      const SparseDeltas sparse = compactDeltas(prim);
      const VkDeviceSize entryBytes = sparse.entries.size() * sizeof(glm::vec4);
      const size_t texels = std::max(sparse.entries.size(), size_t(ranges.restSize / sizeof(float)));
      if (!sparse.entries.empty()) out.largestTexelBuffer_ = std::max(out.largestTexelBuffer_, texels);
      if (!sparse.entries.empty() && texels > limits.maxTexelBufferElements)
        return makeError(ErrorKind::TooLarge, where(model, m, p) + ": " + std::to_string(prim.targets.size()) + " targets x " +
                         std::to_string(prim.vertexCount()) + " vertices need texel buffers of " +
                         std::to_string(texels) + " elements for morphing, the device allows " +
                         std::to_string(limits.maxTexelBufferElements));
      if (!sparse.entries.empty()) {
        ranges.morphOffsetsSize = sparse.offsets.size() * sizeof(uint32_t);
        ranges.morphOffsets = staging.deltas.append(std::span<const uint32_t>(sparse.offsets), storageAlign);
        ranges.morphEntriesSize = entryBytes;
        ranges.morphEntries = staging.deltas.append(std::span<const glm::vec4>(sparse.entries), storageAlign);
      }
      gp.constants.jointSets = static_cast<uint32_t>(prim.influenceSets());
      if (gp.constants.jointSets > 0) ranges.skin = appendInfluences(staging.skin, prim, storageAlign);

      const Material& mat = prim.material >= 0 ? model.materials[static_cast<size_t>(prim.material)] : fallback;
      gp.detailLayers = detailLayers(model, m, p, mat);
      gp.insideTheHead = insideTheHead[m][p];
      if (!gp.detailLayers.empty())
        ranges.detail = staging.detail.append(std::span<const GpuDetailLayer>(gp.detailLayers), storageAlign);

      gp.constants.material = prim.material >= 0 ? static_cast<uint32_t>(prim.material)
                                                 : static_cast<uint32_t>(model.materials.size());
      gp.constants.vertexCount = gp.vertexCount;
      setMaterialConstants(gp.constants, mat, sparse);
      gm.primitives.push_back(gp);
    }
  }
  return out;
}

Result<void> GpuModel::uploadBuffers(const Context& ctx, const GpuModelStaging& staged) {
  const GpuModelStaging::Blobs& staging = *staged.blobs_;
  auto upload = [&](const ByteBlob& blob, VkBufferUsageFlags usage, const char* what, Buffer& out) -> Result<void> {
    if (blob.empty()) return {};
    const std::string label = name_ + " " + what;
    auto buffer = Buffer::createWithData(ctx, blob.bytes(), usage, label.c_str());
    if (!buffer) return buffer.error().prefixed(name_ + ": uploading " + what + ": ");
    out = std::move(buffer).value();
    return {};
  };
  // Vertices are also storage: the morph pre-pass reads the rest attributes.
  ENG_TRY(upload(staging.vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                 "vertices", vertices_));
  ENG_TRY(upload(staging.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices", indices_));
  ENG_TRY(upload(staging.deltas, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "morph deltas", deltas_));
  ENG_TRY(upload(staging.detail, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "detail layers", detailLayers_));
  ENG_TRY(upload(staging.skin, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "joint influences", skinInfluences_));
  return {};
}

// Colour (sRGB: base colour, emissive) and data (linear: metallic-roughness,
// normal, occlusion) images once each, one detail array per material.
Result<void> GpuModel::uploadTextures(const Context& ctx, const Model& model) {
  textures_.resize(model.images.size());
  dataTextures_.resize(model.images.size());
  auto upload = [&](int index, std::vector<GpuImage>& into, VkFormat format) -> Result<void> {
    if (index < 0) return {};
    const eng::Image& img = model.images[static_cast<size_t>(index)];
    GpuImage& tex = into[static_cast<size_t>(index)];
    if (tex || img.rgba8.empty()) return {};  // already uploaded, or undecodable (loader warned): white
    const std::array<std::span<const uint8_t>, 1> layer{img.rgba8};
    const std::string label = name_ + " image '" + img.name + "'";
    auto texture = createTexture(ctx, {static_cast<uint32_t>(img.width), static_cast<uint32_t>(img.height), layer,
                                       VK_IMAGE_VIEW_TYPE_2D, label.c_str(), format});
    if (!texture) return texture.error().prefixed(name_ + ": ");
    tex = std::move(texture).value();
    return {};
  };
  auto addSampler = [&](int image, const TextureSampling& sampling) -> Result<void> {
    if (image < 0 || sampling == TextureSampling{} ||
        std::any_of(samplers_.begin(), samplers_.end(), [&](const auto& s) { return s.first == sampling; }))
      return {};
    auto sampler = createSampler(ctx, sampling);
    if (!sampler) return sampler.error().prefixed(name_ + ": " + describeSampling(sampling) + ": ");
    samplers_.emplace_back(sampling, std::move(sampler).value());
    return {};
  };
  for (const Material& mat : model.materials) {
    ENG_TRY(upload(mat.baseColorImage, textures_, VK_FORMAT_R8G8B8A8_SRGB));
    ENG_TRY(addSampler(mat.baseColorImage, mat.baseColorSampling));
    for (const MaterialTexture& slot : kMaterialTextures) {
      if (slot.colour)
        ENG_TRY(upload(mat.*slot.image, textures_, VK_FORMAT_R8G8B8A8_SRGB));
      else
        ENG_TRY(upload(mat.*slot.image, dataTextures_, VK_FORMAT_R8G8B8A8_UNORM));
      ENG_TRY(addSampler(mat.*slot.image, mat.*slot.sampling));
    }
  }
  detailArrays_.resize(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const Material& mat = model.materials[i];
    const bool usable = !mat.detailLayers.empty() &&
                        std::all_of(mat.detailLayers.begin(), mat.detailLayers.end(), [&](const DetailLayer& l) {
                          return !model.images[static_cast<size_t>(l.image)].rgba8.empty();
                        });
    if (!usable) continue;
    auto array = createDetailArray(ctx, model, mat);
    if (!array) return array.error().prefixed(name_ + ": ");
    detailArrays_[i] = std::move(array).value();
  }
  return {};
}

// One descriptor set per primitive (set 1, scene_layouts.h).
Result<void> GpuModel::createDescriptorSets(const Context& ctx, const SceneLayouts& layouts, const Model& model,
                                           const GpuModelStaging& staging) {
  uint32_t sets = 0;
  for (const GpuMesh& mesh : meshes_) sets += static_cast<uint32_t>(mesh.primitives.size());
  if (sets == 0) return {};
  const std::array poolSizes{VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * sets},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 3 * sets},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 10 * sets}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = sets;
  poolInfo.poolSizeCount = static_cast<uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  descriptorPool_ = UniqueDescriptorPool(ctx.device(), pool);

  const VkDescriptorSetLayout setLayout = layouts.primitiveSetLayout();
  for (size_t m = 0; m < meshes_.size(); ++m) {
    for (size_t p = 0; p < meshes_[m].primitives.size(); ++p) {
      GpuPrimitive& gp = meshes_[m].primitives[p];
      VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      alloc.descriptorPool = pool;
      alloc.descriptorSetCount = 1;
      alloc.pSetLayouts = &setLayout;
      ENG_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &alloc, &gp.descriptorSet));
      const PrimitiveRanges& ranges = staging.ranges_[m][p];
      auto texelView = [&](VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, VkFormat format,
                           VkBufferView placeholder) -> Result<VkBufferView> {
        if (size == 0) return placeholder;
        auto view = createTexelView(ctx, buffer, offset, size, format);
        if (!view) return view.error().prefixed(name_ + ": ");
        return texelViews_.emplace_back(std::move(view).value()).get();
      };
      const bool morphs = ranges.morphEntriesSize > 0;
      auto offsets = texelView(deltas_.handle(), ranges.morphOffsets, ranges.morphOffsetsSize, VK_FORMAT_R32_UINT,
                               layouts.placeholderUintTexels());
      if (!offsets) return offsets.error();
      auto entries = texelView(deltas_.handle(), ranges.morphEntries, ranges.morphEntriesSize,
                               VK_FORMAT_R32G32B32A32_SFLOAT, layouts.placeholderVec4Texels());
      if (!entries) return entries.error();
      auto rest = texelView(vertices_.handle(), ranges.rest, morphs ? ranges.restSize : 0, VK_FORMAT_R32_SFLOAT,
                            layouts.placeholderFloatTexels());
      if (!rest) return rest.error();
      writePrimitiveSet(ctx, layouts, model, model.meshes[m].primitives[p], ranges, {*offsets, *entries, *rest}, gp);
    }
  }
  return {};
}

void GpuModel::writePrimitiveSet(const Context& ctx, const SceneLayouts& layouts, const Model& model,
                                 const Primitive& prim, const PrimitiveRanges& r, const MorphInputViews& morph,
                                 GpuPrimitive& gp) const {
  const GpuImage* base = &layouts.whiteTexture();
  const GpuImage* detail = &layouts.emptyDetailArray();
  VkSampler baseSampler = layouts.sampler();
  // By kMaterialTextures. White: the factors as they are, no occlusion (the
  // normal and emissive textures are read only under their flags).
  std::array<VkDescriptorImageInfo, std::size(kMaterialTextures)> others;
  others.fill({layouts.sampler(), layouts.whiteTexture().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  auto uploaded = [&](const MaterialTexture& slot, int image) -> const GpuImage* {
    if (image < 0) return nullptr;
    const GpuImage& texture = (slot.colour ? textures_ : dataTextures_)[static_cast<size_t>(image)];
    return texture ? &texture : nullptr;
  };
  auto samplerFor = [&](const TextureSampling& wanted, VkSampler& out) {
    for (const auto& [sampling, sampler] : samplers_)
      if (sampling == wanted) out = sampler.get();
  };
  if (prim.material >= 0) {
    const size_t material = static_cast<size_t>(prim.material);
    const Material& mat = model.materials[material];
    if (mat.baseColorImage >= 0 && textures_[static_cast<size_t>(mat.baseColorImage)])
      base = &textures_[static_cast<size_t>(mat.baseColorImage)];
    samplerFor(mat.baseColorSampling, baseSampler);
    for (size_t t = 0; t < others.size(); ++t) {
      const MaterialTexture& slot = kMaterialTextures[t];
      const GpuImage* texture = uploaded(slot, mat.*slot.image);
      if (!texture) continue;
      others[t].imageView = texture->view();
      samplerFor(mat.*slot.sampling, others[t].sampler);
    }
    // Undecodable (the loader warned): drawn as without.
    const auto& [metalRough, normal, occlusion, emissive, matcap, shadingShift, rimMultiply, outlineWidth] =
        kMaterialTextures;
    if (!uploaded(normal, mat.normalImage)) gp.constants.flags &= ~kDrawFlagNormalMap;
    if (!uploaded(occlusion, mat.occlusionImage)) gp.constants.occlusionStrength = 0.0f;
    if (!uploaded(emissive, mat.emissiveImage)) gp.constants.flags &= ~kDrawFlagEmissiveTexture;
    if (!uploaded(matcap, mat.matcapImage)) gp.constants.flags &= ~kDrawFlagToonMatcap;
    if (!uploaded(shadingShift, mat.shadingShiftImage)) gp.constants.flags &= ~kDrawFlagToonShadingShiftTexture;
    if (!uploaded(rimMultiply, mat.rimMultiplyImage)) gp.constants.flags &= ~kDrawFlagToonRimMultiply;
    if (!uploaded(outlineWidth, mat.outlineWidthImage)) gp.constants.flags &= ~kDrawFlagToonOutlineWidthTexture;
    if (detailArrays_[material])
      detail = &detailArrays_[material];
    else
      gp.constants.detailLayerCount = 0;  // layers without decodable images stay off
  }
  const VkBuffer placeholder = layouts.placeholderBuffer().handle();
  const VkDescriptorImageInfo baseInfo{baseSampler, base->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo detailInfo{layouts.sampler(), detail->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorBufferInfo detailParams = rangeOr(
      detailLayers_.handle(), r.detail, gp.constants.detailLayerCount * sizeof(GpuDetailLayer), placeholder);
  const VkDescriptorBufferInfo influences =
      rangeOr(skinInfluences_.handle(), r.skin,
              gp.constants.jointSets > 0 ? prim.joints.size() * 2 * sizeof(glm::uvec4) : 0, placeholder);
  const std::array writes{
      texelBufferWrite(gp.descriptorSet, 0, &morph.offsets),
      texelBufferWrite(gp.descriptorSet, 1, &morph.entries),
      texelBufferWrite(gp.descriptorSet, 2, &morph.rest),
      imageWrite(gp.descriptorSet, 3, &baseInfo),
      imageWrite(gp.descriptorSet, 4, &detailInfo),
      bufferWrite(gp.descriptorSet, 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &detailParams),
      bufferWrite(gp.descriptorSet, 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &influences),
      imageWrite(gp.descriptorSet, 7, &others[0]),
      imageWrite(gp.descriptorSet, 8, &others[1]),
      imageWrite(gp.descriptorSet, 9, &others[2]),
      imageWrite(gp.descriptorSet, 10, &others[3]),
      imageWrite(gp.descriptorSet, 11, &others[4]),
      imageWrite(gp.descriptorSet, 12, &others[5]),
      imageWrite(gp.descriptorSet, 13, &others[6]),
      imageWrite(gp.descriptorSet, 14, &others[7]),
  };
  vkUpdateDescriptorSets(ctx.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void GpuModel::jointMatrices(const MeshNode& node, std::span<const glm::mat4> world, std::vector<glm::mat4>& out) const {
  if (node.skin < 0 || static_cast<size_t>(node.skin) >= skins_.size()) {
    out.clear();
    return;
  }
  skinJointMatrices(skins_[node.skin], world.empty() ? std::span<const glm::mat4>(restWorld_) : world, node.node, out);
}

}  // namespace eng::vk
