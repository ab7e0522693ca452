#include "engine/vk/gpu_model.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <span>
#include <string>

#include "engine/vk/descriptor_write.h"
#include "engine/core/log.h"
#include "engine/scene/crease_shading.h"
#include "engine/scene/face_dressing.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/weights.h"
#include "engine/vk/detail_array.h"
#include "engine/vk/scene_mesh_nodes.h"
#include "engine/vk/texture.h"
#include "engine/vk/vk_result.h"

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

// A material's own parameters, as an instance draws it when nothing moves them.
InstanceMaterial instanceMaterial(const Material& mat) {
  InstanceMaterial out;
  out.baseColorFactor = mat.baseColorFactor;
  out.emissive = glm::vec4(mat.emissiveFactor, 0.0f);
  return out;
}

// Appends byte ranges at aligned offsets; the result becomes one buffer.
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

std::string where(const Model& model, size_t mesh, size_t primitive) {
  std::string file = model.sourcePath.empty() ? std::string("<model>") : model.sourcePath;
  return file + ": mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

// Target-major, vertex-minor float-tight deltas of one attribute (see morph.glsl).
template <class Select>
VkDeviceSize appendDeltas(ByteBlob& blob, const Primitive& prim, Select select, VkDeviceSize alignment) {
  const size_t vertexCount = prim.vertexCount();
  const size_t targetBytes = vertexCount * sizeof(glm::vec3);
  const VkDeviceSize offset = blob.append(nullptr, targetBytes * prim.targets.size(), alignment);
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const std::vector<glm::vec3>& deltas = select(prim.targets[t]);
    if (!deltas.empty()) std::memcpy(blob.range(offset + t * targetBytes, targetBytes).data(), deltas.data(), targetBytes);
  }
  return offset;
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

struct DeltaRanges {
  VkDeviceSize position = 0, normal = 0, tangent = 0, crease = 0;
  VkDeviceSize size = 0;         // bytes of one attribute's range
  VkDeviceSize creaseSize = 0;   // bytes of the crease darkening
  bool hasTargets = false, hasNormals = false, hasTangents = false;
};

}  // namespace

Result<void> validateModelForGpu(const Model& model) {
  const std::string file = model.sourcePath.empty() ? std::string("<model>") : model.sourcePath;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      const size_t n = prim.vertexCount();
      auto fail = [&](const std::string& what) { return makeError(ErrorKind::Malformed, where(model, m, p) + ": " + what); };
      if (n == 0) return fail("has no vertices");
      if (n > UINT32_MAX / 4) return fail("has " + std::to_string(n) + " vertices, too many");
      if (prim.normals.size() != n)
        return fail(std::to_string(prim.normals.size()) + " normals for " + std::to_string(n) + " vertices");
      if (!prim.texcoords.empty() && prim.texcoords.size() != n)
        return fail(std::to_string(prim.texcoords.size()) + " texcoords for " + std::to_string(n) + " vertices");
      if (!prim.tangents.empty() && prim.tangents.size() != n)
        return fail(std::to_string(prim.tangents.size()) + " tangents for " + std::to_string(n) + " vertices");
      if (prim.indices.empty() || prim.indices.size() % 3 != 0)
        return fail(std::to_string(prim.indices.size()) + " indices is not a non-empty triangle list");
      for (uint32_t index : prim.indices) {
        if (index >= n) return fail("index " + std::to_string(index) + " >= vertex count " + std::to_string(n));
      }
      if (prim.targets.size() != mesh.targetNames.size())
        return fail(std::to_string(prim.targets.size()) + " morph targets but the mesh names " +
                    std::to_string(mesh.targetNames.size()));
      for (size_t t = 0; t < prim.targets.size(); ++t) {
        const MorphTarget& target = prim.targets[t];
        for (const auto* arr : {&target.positions, &target.normals, &target.tangents}) {
          if (!arr->empty() && arr->size() != n)
            return fail("target " + std::to_string(t) + " has an attribute with " + std::to_string(arr->size()) +
                        " deltas for " + std::to_string(n) + " vertices");
        }
      }
      if (prim.joints.size() != prim.jointWeights.size() || prim.joints.size() % n != 0)
        return fail(std::to_string(prim.joints.size()) + " joint groups and " + std::to_string(prim.jointWeights.size()) +
                    " weight groups for " + std::to_string(n) + " vertices");
      if (prim.material < -1 || prim.material >= static_cast<int>(model.materials.size()))
        return fail("material " + std::to_string(prim.material) + " out of range (" +
                    std::to_string(model.materials.size()) + " materials)");
    }
  }
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const Material& mat = model.materials[i];
    auto badImage = [&](int image) { return image < -1 || image >= static_cast<int>(model.images.size()); };
    if (badImage(mat.baseColorImage))
      return makeError(ErrorKind::Malformed, file + ": material " + std::to_string(i) + " base colour image " +
                       std::to_string(mat.baseColorImage) + " out of range (" + std::to_string(model.images.size()) +
                       " images)");
    for (const DetailLayer& layer : mat.detailLayers) {
      if (layer.image < 0 || badImage(layer.image))
        return makeError(ErrorKind::Malformed, file + ": material " + std::to_string(i) + " detail layer '" + layer.target + "' image " +
                         std::to_string(layer.image) + " out of range (" + std::to_string(model.images.size()) +
                         " images)");
    }
  }
  for (const eng::Image& img : model.images) {
    if (!img.rgba8.empty() && img.rgba8.size() != size_t(img.width) * size_t(img.height) * 4)
      return makeError(ErrorKind::Malformed, file + ": image '" + img.name + "' has " + std::to_string(img.rgba8.size()) + " bytes for " +
                       std::to_string(img.width) + "x" + std::to_string(img.height) + " RGBA8");
  }
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const Node& node = model.nodes[i];
    if (node.mesh < -1 || node.mesh >= static_cast<int>(model.meshes.size()))
      return makeError(ErrorKind::Malformed, file + ": node " + std::to_string(i) + " mesh " + std::to_string(node.mesh) +
                       " out of range (" + std::to_string(model.meshes.size()) + " meshes)");
    if (node.skin < -1 || node.skin >= static_cast<int>(model.skins.size()))
      return makeError(ErrorKind::Malformed, file + ": node " + std::to_string(i) + " skin " + std::to_string(node.skin) +
                       " out of range (" + std::to_string(model.skins.size()) + " skins)");
    for (int child : node.children) {
      if (child < 0 || child >= static_cast<int>(model.nodes.size()))
        return makeError(ErrorKind::Malformed, file + ": node " + std::to_string(i) + " child " + std::to_string(child) + " out of range");
    }
  }
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const Skin& skin = model.skins[s];
    if (skin.inverseBindMatrices.size() != skin.joints.size())
      return makeError(ErrorKind::Malformed, file + ": skin " + std::to_string(s) + " has " + std::to_string(skin.inverseBindMatrices.size()) +
                       " inverse bind matrices for " + std::to_string(skin.joints.size()) + " joints");
    for (int joint : skin.joints)
      if (joint < 0 || joint >= static_cast<int>(model.nodes.size()))
        return makeError(ErrorKind::Malformed, file + ": skin " + std::to_string(s) + " joint " + std::to_string(joint) + " out of range");
  }
  for (int root : model.roots) {
    if (root < 0 || root >= static_cast<int>(model.nodes.size()))
      return makeError(ErrorKind::Malformed, file + ": scene root " + std::to_string(root) + " out of range");
  }
  return {};
}

Result<GpuModel> GpuModel::create(const Context& ctx, const SceneLayouts& layouts, const Model& source) {
  ENG_TRY(validateModelForGpu(source));
  // An untextured face is dressed for display only: the CPU model (what
  // tools inspect and export) stays as loaded.
  std::optional<Model> dressed;
  if (planFaceDressing(source).total() > 0) {
    dressed = source;
    dressUntexturedFace(*dressed);
  }
  const Model& model = dressed ? *dressed : source;
  const std::string file = model.sourcePath.empty() ? std::string("<model>") : model.sourcePath;
  const VkPhysicalDeviceLimits& limits = ctx.deviceInfo().properties.limits;
  const VkDeviceSize storageAlign = std::max<VkDeviceSize>(limits.minStorageBufferOffsetAlignment, 16);

  GpuModel gpu;
  gpu.name_ = file;
  gpu.bounds_ = model.skins.empty() ? model.bounds() : posedBounds(model, restPose(model));
  const WeightLayout weightLayout(model);
  gpu.weightCount_ = weightLayout.total();

  gpu.materialCount_ = static_cast<uint32_t>(source.materials.size());
  for (const Material& mat : model.materials) gpu.materials_.push_back(instanceMaterial(mat));
  gpu.materials_.push_back(instanceMaterial(defaultMaterial()));
  gpu.meshNodes_ = sceneMeshNodes(model);
  gpu.skins_ = model.skins;
  poseWorldMatrices(model, restPose(model), gpu.restWorld_);

  // --- Geometry, deltas and detail-layer parameters, laid out in three blobs ---
  const Material fallback = defaultMaterial();
  ByteBlob vertexBlob, indexBlob, deltaBlob, detailBlob, skinBlob;
  std::vector<std::vector<VkDeviceSize>> skinOffsets(model.meshes.size());
  std::vector<std::vector<DeltaRanges>> deltaRanges(model.meshes.size());
  std::vector<std::vector<VkDeviceSize>> detailOffsets(model.meshes.size());
  gpu.meshes_.resize(model.meshes.size());
  size_t primitiveCount = 0;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    GpuMesh& gm = gpu.meshes_[m];
    gm.name = mesh.name;
    gm.targetCount = static_cast<uint32_t>(mesh.targetNames.size());
    gm.weightOffset = weightLayout.offset(static_cast<int>(m));
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      const size_t n = prim.vertexCount();
      GpuPrimitive gp;
      gp.vertexCount = static_cast<uint32_t>(n);
      gp.indexCount = static_cast<uint32_t>(prim.indices.size());
      gp.positionOffset = vertexBlob.append(std::span(prim.positions), 16);
      gp.normalOffset = vertexBlob.append(std::span(prim.normals), 16);
      gp.texcoordOffset = prim.texcoords.empty() ? vertexBlob.append(nullptr, n * sizeof(glm::vec2), 16)
                                                 : vertexBlob.append(std::span(prim.texcoords), 16);
      gp.tangentOffset = prim.tangents.empty() ? vertexBlob.append(nullptr, n * sizeof(glm::vec4), 16)
                                               : vertexBlob.append(std::span(prim.tangents), 16);
      if (prim.colors.size() == n) {
        gp.colorOffset = vertexBlob.append(std::span(prim.colors), 16);
      } else {
        const std::vector<glm::vec4> white(n, glm::vec4(1.0f));
        gp.colorOffset = vertexBlob.append(std::span(white), 16);
      }
      gp.indexOffset = indexBlob.append(std::span(prim.indices), 16);

      DeltaRanges ranges;
      ranges.hasTargets = !prim.targets.empty();
      ranges.size = prim.targets.size() * n * sizeof(glm::vec3);
      for (const MorphTarget& t : prim.targets) {
        ranges.hasNormals |= !t.normals.empty();
        ranges.hasTangents |= !t.tangents.empty();
      }
      if (ranges.hasTargets && ranges.size > limits.maxStorageBufferRange)
        return makeError(ErrorKind::TooLarge, where(model, m, p) + ": " + std::to_string(prim.targets.size()) + " targets x " +
                         std::to_string(n) + " vertices need " + std::to_string(ranges.size) +
                         " bytes of deltas per attribute, the device allows " +
                         std::to_string(limits.maxStorageBufferRange));
      if (ranges.hasTargets)
        ranges.position = appendDeltas(deltaBlob, prim, [](const MorphTarget& t) -> auto& { return t.positions; },
                                       storageAlign);
      if (ranges.hasNormals)
        ranges.normal = appendDeltas(deltaBlob, prim, [](const MorphTarget& t) -> auto& { return t.normals; },
                                     storageAlign);
      if (ranges.hasTangents)
        ranges.tangent = appendDeltas(deltaBlob, prim, [](const MorphTarget& t) -> auto& { return t.tangents; },
                                      storageAlign);
      if (ranges.hasTargets) {
        const std::vector<float> darkening = bakeCreaseDarkening(prim);
        if (hasCreases(darkening)) {
          ranges.creaseSize = darkening.size() * sizeof(float);
          ranges.crease = deltaBlob.append(std::span<const float>(darkening), storageAlign);
        }
      }
      deltaRanges[m].push_back(ranges);
      gp.constants.jointSets = static_cast<uint32_t>(prim.influenceSets());
      skinOffsets[m].push_back(gp.constants.jointSets > 0 ? appendInfluences(skinBlob, prim, storageAlign) : 0);

      const Material& mat = prim.material >= 0 ? model.materials[static_cast<size_t>(prim.material)] : fallback;
      std::vector<GpuDetailLayer> layers;
      for (const DetailLayer& layer : mat.detailLayers) {
        auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), layer.target);
        if (it == mesh.targetNames.end())
          logWarning(where(model, m, p) + ": detail layer target '" + layer.target +
                     "' is not a morph target of this mesh; the layer stays hidden");
        // UINT32_MAX never matches an active target, so a missing target reads as weight 0.
        layers.push_back({it == mesh.targetNames.end() ? UINT32_MAX
                                                       : static_cast<uint32_t>(it - mesh.targetNames.begin()),
                          layer.strength});
      }
      detailOffsets[m].push_back(layers.empty() ? 0 : detailBlob.append(std::span<const GpuDetailLayer>(layers),
                                                                        storageAlign));

      gp.constants.material = prim.material >= 0 ? static_cast<uint32_t>(prim.material)
                                                 : static_cast<uint32_t>(model.materials.size());
      gp.constants.roughness = mat.roughness;
      gp.constants.metallic = mat.metallic;
      gp.constants.detailLayerCount = static_cast<uint32_t>(mat.detailLayers.size());
      gp.constants.vertexCount = gp.vertexCount;
      gp.constants.flags = (ranges.hasNormals ? kDrawFlagNormalDeltas : 0u) |
                           (ranges.hasTangents ? kDrawFlagTangentDeltas : 0u) |
                           (mat.doubleSided ? kDrawFlagDoubleSided : 0u) |
                           (ranges.creaseSize > 0 ? kDrawFlagCreases : 0u);
      gm.primitives.push_back(gp);
      ++primitiveCount;
    }
  }

  auto upload = [&](const ByteBlob& blob, VkBufferUsageFlags usage, const char* what, Buffer& out) -> Result<void> {
    if (blob.empty()) return {};
    const std::string name = file + " " + what;
    auto buffer = Buffer::createWithData(ctx, blob.bytes(), usage, name.c_str());
    if (!buffer) return buffer.error().prefixed(file + ": uploading " + what + ": ");
    out = std::move(buffer).value();
    return {};
  };
  ENG_TRY(upload(vertexBlob, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertices", gpu.vertices_));
  ENG_TRY(upload(indexBlob, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices", gpu.indices_));
  ENG_TRY(upload(deltaBlob, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "morph deltas", gpu.deltas_));
  ENG_TRY(upload(detailBlob, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "detail layers", gpu.detailLayers_));
  ENG_TRY(upload(skinBlob, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "joint influences", gpu.skinInfluences_));

  // --- Textures: base colour images once each, one detail array per material ---
  gpu.textures_.resize(model.images.size());
  for (const Material& mat : model.materials) {
    if (mat.baseColorImage < 0) continue;
    const eng::Image& img = model.images[static_cast<size_t>(mat.baseColorImage)];
    GpuImage& tex = gpu.textures_[static_cast<size_t>(mat.baseColorImage)];
    if (tex || img.rgba8.empty()) continue;  // already uploaded, or undecodable (loader warned): white
    const std::array<std::span<const uint8_t>, 1> layer{img.rgba8};
    const std::string name = file + " image '" + img.name + "'";
    auto texture = createTexture(ctx, {static_cast<uint32_t>(img.width), static_cast<uint32_t>(img.height), layer,
                                       VK_IMAGE_VIEW_TYPE_2D, name.c_str()});
    if (!texture) return texture.error().prefixed(file + ": ");
    tex = std::move(texture).value();
  }
  gpu.detailArrays_.resize(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const Material& mat = model.materials[i];
    const bool usable = !mat.detailLayers.empty() &&
                        std::all_of(mat.detailLayers.begin(), mat.detailLayers.end(), [&](const DetailLayer& l) {
                          return !model.images[static_cast<size_t>(l.image)].rgba8.empty();
                        });
    if (!usable) continue;
    auto array = createDetailArray(ctx, model, mat);
    if (!array) return array.error().prefixed(file + ": ");
    gpu.detailArrays_[i] = std::move(array).value();
  }

  // --- Descriptor sets, one per primitive ---
  if (primitiveCount == 0) return gpu;
  const uint32_t sets = static_cast<uint32_t>(primitiveCount);
  const std::array poolSizes{VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6 * sets},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * sets}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = sets;
  poolInfo.poolSizeCount = static_cast<uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  gpu.descriptorPool_ = UniqueDescriptorPool(ctx.device(), pool);

  const VkBuffer placeholder = layouts.placeholderBuffer().handle();
  for (size_t m = 0; m < gpu.meshes_.size(); ++m) {
    for (size_t p = 0; p < gpu.meshes_[m].primitives.size(); ++p) {
      GpuPrimitive& gp = gpu.meshes_[m].primitives[p];
      const Primitive& prim = model.meshes[m].primitives[p];
      const DeltaRanges& r = deltaRanges[m][p];
      const VkDescriptorSetLayout setLayout = layouts.primitiveSetLayout();
      VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      alloc.descriptorPool = pool;
      alloc.descriptorSetCount = 1;
      alloc.pSetLayouts = &setLayout;
      ENG_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &alloc, &gp.descriptorSet));

      auto deltaInfo = [&](bool present, VkDeviceSize offset) {
        return present ? VkDescriptorBufferInfo{gpu.deltas_.handle(), offset, r.size}
                       : VkDescriptorBufferInfo{placeholder, 0, VK_WHOLE_SIZE};
      };
      const VkDescriptorBufferInfo positions = deltaInfo(r.hasTargets, r.position);
      const VkDescriptorBufferInfo normals = deltaInfo(r.hasNormals, r.normal);
      const VkDescriptorBufferInfo tangents = deltaInfo(r.hasTangents, r.tangent);
      const VkDescriptorBufferInfo creases = r.creaseSize > 0
                                                 ? VkDescriptorBufferInfo{gpu.deltas_.handle(), r.crease, r.creaseSize}
                                                 : VkDescriptorBufferInfo{placeholder, 0, VK_WHOLE_SIZE};
      const int materialIndex = prim.material;
      const GpuImage* base = &layouts.whiteTexture();
      const GpuImage* detail = &layouts.emptyDetailArray();
      if (materialIndex >= 0) {
        const Material& mat = model.materials[static_cast<size_t>(materialIndex)];
        if (mat.baseColorImage >= 0 && gpu.textures_[static_cast<size_t>(mat.baseColorImage)])
          base = &gpu.textures_[static_cast<size_t>(mat.baseColorImage)];
        if (gpu.detailArrays_[static_cast<size_t>(materialIndex)])
          detail = &gpu.detailArrays_[static_cast<size_t>(materialIndex)];
        else
          gp.constants.detailLayerCount = 0;  // layers without decodable images stay off
      }
      const VkDescriptorImageInfo baseInfo{layouts.sampler(), base->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      const VkDescriptorImageInfo detailInfo{layouts.sampler(), detail->view(),
                                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      const VkDescriptorBufferInfo detailParams =
          gp.constants.detailLayerCount > 0
              ? VkDescriptorBufferInfo{gpu.detailLayers_.handle(), detailOffsets[m][p],
                                       gp.constants.detailLayerCount * sizeof(GpuDetailLayer)}
              : VkDescriptorBufferInfo{placeholder, 0, VK_WHOLE_SIZE};
      const VkDescriptorBufferInfo influences =
          gp.constants.jointSets > 0
              ? VkDescriptorBufferInfo{gpu.skinInfluences_.handle(), skinOffsets[m][p],
                                       prim.joints.size() * 2 * sizeof(glm::uvec4)}
              : VkDescriptorBufferInfo{placeholder, 0, VK_WHOLE_SIZE};

      const std::array writes{
          bufferWrite(gp.descriptorSet, 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &positions),
          bufferWrite(gp.descriptorSet, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &normals),
          bufferWrite(gp.descriptorSet, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &tangents),
          imageWrite(gp.descriptorSet, 3, &baseInfo),
          imageWrite(gp.descriptorSet, 4, &detailInfo),
          bufferWrite(gp.descriptorSet, 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &detailParams),
          bufferWrite(gp.descriptorSet, 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &influences),
          bufferWrite(gp.descriptorSet, 7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &creases),
      };
      vkUpdateDescriptorSets(ctx.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    }
  }
  return gpu;
}

void GpuModel::jointMatrices(const MeshNode& node, std::span<const glm::mat4> world, std::vector<glm::mat4>& out) const {
  if (node.skin < 0 || static_cast<size_t>(node.skin) >= skins_.size()) {
    out.clear();
    return;
  }
  skinJointMatrices(skins_[node.skin], world.empty() ? std::span<const glm::mat4>(restWorld_) : world, node.node, out);
}

}  // namespace eng::vk
