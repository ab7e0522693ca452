#include "engine/vk/draw/scene_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/gtc/matrix_inverse.hpp>

#include "engine/vk/device/descriptor_write.h"
#include "engine/core/fnv1a.h"
#include "engine/core/log.h"
#include "engine/vk/draw/active_weights.h"
#include "engine/vk/device/vk_result.h"

namespace eng::vk {
namespace {

// morph.comp's local_size_x (256 measured no faster on lavapipe).
constexpr uint32_t kMorphGroupSize = 64;

// glTF: a node transform with a negative determinant turns the winding of
// its triangles (a mesh mirrored with scale -1, common in exported rigs).
bool isMirrored(const glm::mat4& transform) { return glm::determinant(glm::mat3(transform)) < 0.0f; }

// The morph pre-pass's output per vertex (morph.glsl): position + crease,
// normal, and the tangent where the primitive has tangent deltas.
uint32_t morphedVec4sPerVertex(const GpuPrimitive& prim) {
  return (prim.constants.flags & kDrawFlagTangentDeltas) != 0 ? 3 : 2;
}

}  // namespace

Result<SceneRenderer> SceneRenderer::create(const Context& ctx, const SceneLayouts& layouts,
                                            const ShaderLibrary& shaders, VkRenderPass renderPass,
                                            VkSampleCountFlagBits samples, uint32_t frameSlots,
                                            RenderQuality quality) {
  if (frameSlots == 0) return makeError(ErrorKind::InvalidArgument, "scene renderer: frameSlots must be >= 1");
  SceneRenderer r;
  r.ctx_ = &ctx;
  r.layouts_ = &layouts;
  r.shaders_ = &shaders;
  r.renderPass_ = renderPass;
  r.samples_ = samples;
  r.quality_ = quality;
  const QualitySettings settings = qualitySettings(quality);
  // Without shadows a token map stays bound (the descriptor needs an image in
  // its read layout); its pass only clears it.
  auto shadowMap = ShadowMap::create(ctx, settings.shadowMapSize > 0 ? settings.shadowMapSize : 16);
  if (!shadowMap) return shadowMap.error();
  r.shadowMap_ = std::move(shadowMap).value();
  auto pipelines =
      ScenePipelines::create(ctx, layouts, shaders, renderPass, samples, r.shadowMap_.renderPass(), settings);
  if (!pipelines) return pipelines.error();
  r.pipelines_ = std::move(pipelines).value();
  r.pipelineGeneration_ = shaders.generation();

  const std::array poolSizes{VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frameSlots},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6 * frameSlots},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, frameSlots},
                             VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, frameSlots}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = frameSlots;
  poolInfo.poolSizeCount = static_cast<uint32_t>(poolSizes.size());
  poolInfo.pPoolSizes = poolSizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
  r.descriptorPool_ = UniqueDescriptorPool(ctx.device(), pool);

  r.slots_.resize(frameSlots);
  for (Slot& slot : r.slots_) {
    const VkDescriptorSetLayout setLayout = layouts.frameSetLayout();
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &setLayout;
    ENG_VK_TRY(vkAllocateDescriptorSets(ctx.device(), &alloc, &slot.descriptorSet));
    auto globals = Buffer::create(ctx, sizeof(FrameGlobals), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Upload,
                                  "frame globals");
    if (!globals) return globals.error();
    slot.globals = std::move(globals).value();
    auto instances = Buffer::create(ctx, 64 * sizeof(GpuInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    MemoryUsage::Upload, "instances");
    if (!instances) return instances.error();
    slot.instances = std::move(instances).value();
    auto active = Buffer::create(ctx, 1024 * sizeof(ActiveWeight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 MemoryUsage::Upload, "active weights");
    if (!active) return active.error();
    slot.active = std::move(active).value();
    auto joints = Buffer::create(ctx, 64 * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload,
                                 "joint matrices");
    if (!joints) return joints.error();
    slot.joints = std::move(joints).value();
    auto materials = Buffer::create(ctx, 16 * sizeof(InstanceMaterial), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    MemoryUsage::Upload, "instance materials");
    if (!materials) return materials.error();
    slot.materials = std::move(materials).value();
    auto weights = Buffer::create(ctx, 256 * sizeof(float), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                  MemoryUsage::Upload, "target weights");
    if (!weights) return weights.error();
    slot.weights = std::move(weights).value();
    auto morphed = Buffer::create(ctx, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly,
                                  "morphed vertices");
    if (!morphed) return morphed.error();
    slot.morphed = std::move(morphed).value();
    ENG_TRY(r.writeDescriptors(slot));
  }
  return r;
}

Result<void> SceneRenderer::ensureCapacity(Slot& slot, Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                                           MemoryUsage memory, const char* name) {
  if (buffer && buffer.size() >= bytes) return {};
  // Grow geometrically so a slowly growing scene reallocates rarely.
  const VkDeviceSize size = std::max<VkDeviceSize>(bytes, buffer ? buffer.size() * 2 : bytes);
  auto grown = Buffer::create(*ctx_, std::max<VkDeviceSize>(size, 256), usage, memory, name);
  if (!grown) return grown.error();
  buffer = std::move(grown).value();
  return writeDescriptors(slot);
}

Result<void> SceneRenderer::writeDescriptors(Slot& slot) const {
  auto weightTexels = createTexelView(*ctx_, slot.weights.handle(), 0, VK_WHOLE_SIZE, VK_FORMAT_R32_SFLOAT);
  if (!weightTexels) return weightTexels.error();
  slot.weightTexels = std::move(weightTexels).value();
  const VkBufferView weights = slot.weightTexels.get();
  const VkDescriptorBufferInfo globals{slot.globals.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo instances{slot.instances.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo active{slot.active.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo joints{slot.joints.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo materials{slot.materials.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo capture{slot.capture ? slot.capture.handle() : layouts_->placeholderBuffer().handle(),
                                       0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo morphed{slot.morphed.handle(), 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo shadow{shadowMap_.sampler(), shadowMap_.view(),
                                     VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
  const std::array writes{
      bufferWrite(slot.descriptorSet, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &globals),
      bufferWrite(slot.descriptorSet, 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &instances),
      bufferWrite(slot.descriptorSet, 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &active),
      bufferWrite(slot.descriptorSet, 3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &capture),
      imageWrite(slot.descriptorSet, 4, &shadow),
      bufferWrite(slot.descriptorSet, 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &joints),
      bufferWrite(slot.descriptorSet, 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &materials),
      bufferWrite(slot.descriptorSet, 7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &morphed),
      texelBufferWrite(slot.descriptorSet, 8, &weights),
  };
  vkUpdateDescriptorSets(ctx_->device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  return {};
}

// The steps of laying out one frame: each fills the scratch vectors for the
// model being laid out (modelScratch_ order), which upload() then copies into
// the slot's buffers.
Result<void> SceneRenderer::build(uint32_t slotIndex, std::span<const ModelInstance> instances, Mode mode) {
  if (slotIndex >= slots_.size())
    return makeError(ErrorKind::InvalidArgument, "scene renderer: frame slot " + std::to_string(slotIndex) + " of " +
                     std::to_string(slots_.size()));
  Slot& slot = slots_[slotIndex];
  clearLayout(slot);
  ENG_TRY(checkInstances(instances));
  for (const GpuModel* model : modelScratch_) {
    const ModelLayout at{*model, instances, mode, gatherMembers(slot, *model, instances)};
    layOutMaterials(at);
    layOutWeights(at);
    ENG_TRY(listActiveWeights(at));
    jointSetScratch_.assign(memberScratch_.size(), JointSet{});
    if (mode == Mode::Draw) {
      for (const MeshNode& node : model->meshNodes()) addMeshBatches(slot, at, static_cast<uint32_t>(node.mesh), &node);
    } else {
      // Every mesh once, posed by the first scene node that draws it (if any).
      const auto nodes = model->meshNodes();
      for (uint32_t m = 0; m < model->meshes().size(); ++m) {
        const auto first = std::find_if(nodes.begin(), nodes.end(), [&](const MeshNode& n) { return n.mesh == int(m); });
        addMeshBatches(slot, at, m, first == nodes.end() ? nullptr : &*first);
      }
    }
  }
  return upload(slot, mode);
}

// A new frame in the slot: no batches, and scratch kept only for its capacity.
void SceneRenderer::clearLayout(Slot& slot) {
  slot.batches.clear();
  slot.members.clear();
  slot.capturedVertices = 0;
  slot.morphedVec4s = 0;
  instanceScratch_.clear();
  mirroredScratch_.clear();
  activeScratch_.clear();
  weightScratch_.clear();
  jointScratch_.clear();
  materialScratch_.clear();
  modelScratch_.clear();
}

// The caller's instances, refused by index and model before anything is laid
// out; collects the distinct models in modelScratch_ (first use first).
Result<void> SceneRenderer::checkInstances(std::span<const ModelInstance> instances) {
  for (size_t i = 0; i < instances.size(); ++i) {
    const ModelInstance& inst = instances[i];
    if (!inst.model) return makeError(ErrorKind::InvalidArgument, "instance " + std::to_string(i) + ": no model");
    // Made only for a refusal: a frame that passes allocates nothing.
    auto refuse = [&](const std::string& what) {
      return makeError(ErrorKind::InvalidArgument, "instance " + std::to_string(i) + " (" + inst.model->name() + "): " + what);
    };
    if (inst.weights.size() != inst.model->weightCount())
      return refuse(std::to_string(inst.weights.size()) + " weights given, the model has " +
                    std::to_string(inst.model->weightCount()));
    if (!inst.nodeWorld.empty() && inst.nodeWorld.size() != inst.model->nodeCount())
      return refuse("pose of " + std::to_string(inst.nodeWorld.size()) + " nodes given, the model has " +
                    std::to_string(inst.model->nodeCount()));
    if (inst.materials.size() > inst.model->materialCount())
      return refuse(std::to_string(inst.materials.size()) + " materials given, the model has " +
                    std::to_string(inst.model->materialCount()));
    for (size_t m = 0; m < inst.materials.size(); ++m) {
      const InstanceMaterial& mat = inst.materials[m];
      const glm::vec4 sum = mat.baseColorFactor + mat.emissive + mat.uvTransform + mat.toonShade + mat.toonShading +
                            mat.toonRim + mat.toonOutline + mat.toonOutlineStyle + mat.toonMatcap;
      if (!std::isfinite(sum.x + sum.y + sum.z + sum.w))
        return refuse("material " + std::to_string(m) + " has a non-finite value");
    }
    if (std::find(modelScratch_.begin(), modelScratch_.end(), inst.model) == modelScratch_.end())
      modelScratch_.push_back(inst.model);
  }
  return {};
}

// The model's instances (memberScratch_), mirrored placements after the
// others: a draw covers a run of instances that wind the same way
// (addPrimitiveBatches), so they make one run, not many. Returns where they
// start in slot.members.
uint32_t SceneRenderer::gatherMembers(Slot& slot, const GpuModel& model, std::span<const ModelInstance> instances) {
  memberScratch_.clear();
  for (size_t i = 0; i < instances.size(); ++i)
    if (instances[i].model == &model) memberScratch_.push_back(static_cast<uint32_t>(i));
  std::stable_partition(memberScratch_.begin(), memberScratch_.end(),
                        [&](uint32_t i) { return !isMirrored(instances[i].transform); });
  const uint32_t membersOffset = static_cast<uint32_t>(slot.members.size());
  slot.members.insert(slot.members.end(), memberScratch_.begin(), memberScratch_.end());
  return membersOffset;
}

// Every member's material records: the model's own, then the member's overrides.
void SceneRenderer::layOutMaterials(const ModelLayout& at) {
  const std::span<const InstanceMaterial> rest = at.model.materials();
  materialOffsetScratch_.clear();
  for (uint32_t member : memberScratch_) {
    const size_t start = materialScratch_.size();
    materialOffsetScratch_.push_back(static_cast<uint32_t>(start));
    materialScratch_.insert(materialScratch_.end(), rest.begin(), rest.end());
    const std::span<const InstanceMaterial> own = at.instances[member].materials;
    std::copy(own.begin(), own.end(), materialScratch_.begin() + std::ptrdiff_t(start));
  }
}

// Every member's weights as the morph pre-pass reads them: zero where the
// active list (listActiveWeights) has no entry, so both sum the same terms.
void SceneRenderer::layOutWeights(const ModelLayout& at) {
  weightOffsetScratch_.clear();
  for (uint32_t member : memberScratch_) {
    weightOffsetScratch_.push_back(static_cast<uint32_t>(weightScratch_.size()));
    for (float w : at.instances[member].weights) weightScratch_.push_back(std::abs(w) >= kActiveWeightThreshold ? w : 0.0f);
  }
}

// The active list of every (member, mesh), and its range in rangeScratch_.
Result<void> SceneRenderer::listActiveWeights(const ModelLayout& at) {
  const std::span<const GpuMesh> meshes = at.model.meshes();
  rangeScratch_.assign(memberScratch_.size() * meshes.size(), {});
  for (size_t k = 0; k < memberScratch_.size(); ++k) {
    const ModelInstance& inst = at.instances[memberScratch_[k]];
    for (size_t m = 0; m < meshes.size(); ++m) {
      const size_t start = activeScratch_.size();
      activeScratch_.resize(start + meshes[m].targetCount);
      ActiveWeightsJob job{inst.weights.subspan(meshes[m].weightOffset, meshes[m].targetCount),
                           std::span(activeScratch_).subspan(start)};
      if (auto valid = job.Validate(); !valid)
        return valid.error().prefixed("instance " + std::to_string(memberScratch_[k]) + " (" + at.model.name() + ") mesh " +
                                      std::to_string(m) + ": ");
      const uint32_t count = job.Run();
      activeScratch_.resize(start + count);
      rangeScratch_[k * meshes.size() + m] = {static_cast<uint32_t>(start), count};
    }
  }
  return {};
}

// node: the mesh node drawn (its pose and skin), or null (capture of a mesh no scene node draws).
void SceneRenderer::addMeshBatches(Slot& slot, const ModelLayout& at, uint32_t mesh, const MeshNode* node) {
  const uint32_t firstInstance = static_cast<uint32_t>(instanceScratch_.size());
  for (size_t k = 0; k < memberScratch_.size(); ++k) addInstanceRecord(at, k, mesh, node);
  addPrimitiveBatches(slot, at, mesh, firstInstance);
}

// Member k's record for one mesh: its transform, its slices of the active
// list, weights, materials and joint matrices; and whether it mirrors.
void SceneRenderer::addInstanceRecord(const ModelLayout& at, size_t k, uint32_t mesh, const MeshNode* node) {
  const ModelInstance& inst = at.instances[memberScratch_[k]];
  const std::span<const GpuMesh> meshes = at.model.meshes();
  GpuInstance record;
  if (at.mode == Mode::Draw) record.model = inst.transform * (inst.nodeWorld.empty() ? node->world : inst.nodeWorld[node->node]);
  record.normalMatrix = glm::mat4(glm::inverseTranspose(glm::mat3(record.model)));
  const ActiveRange range = rangeScratch_[k * meshes.size() + mesh];
  record.activeOffset = range.offset;
  record.activeCount = range.count;
  record.materialOffset = materialOffsetScratch_[k];
  record.weightOffset = weightOffsetScratch_[k] + meshes[mesh].weightOffset;
  if (node && node->skin >= 0) {
    const JointSet& set = memberJoints(at, k, *node);
    record.jointOffset = set.offset;
    record.jointCount = set.count;
  }
  // The transform the vertices finally see: a skin's joint matrices
  // undo the mesh node's own (skinJointMatrices).
  const bool skinned = record.jointCount > 0;
  const glm::mat4 placed = skinned ? record.model * jointScratch_[record.jointOffset] : record.model;
  mirroredScratch_.push_back(at.mode == Mode::Draw && isMirrored(placed));
  instanceScratch_.push_back(record);
}

// A character split into parts (mesh nodes) under one node gives every part
// the same joint matrices: made and uploaded once per member, not once per
// part (a Ready Player Me avatar has six or more).
const SceneRenderer::JointSet& SceneRenderer::memberJoints(const ModelLayout& at, size_t k, const MeshNode& node) {
  const ModelInstance& inst = at.instances[memberScratch_[k]];
  const glm::mat4& meshWorld = inst.nodeWorld.empty() ? node.world : inst.nodeWorld[node.node];
  JointSet& set = jointSetScratch_[k];
  if (set.skin != node.skin || set.meshWorld != meshWorld) {
    at.model.jointMatrices(node, inst.nodeWorld, skinScratch_);
    set = {node.skin, meshWorld, static_cast<uint32_t>(jointScratch_.size()), static_cast<uint32_t>(skinScratch_.size())};
    jointScratch_.insert(jointScratch_.end(), skinScratch_.begin(), skinScratch_.end());
  }
  return set;
}

// One draw per primitive of the mesh per run of members that wind the same
// way (the winding is pipeline state), and room for their morphed and
// captured vertices.
void SceneRenderer::addPrimitiveBatches(Slot& slot, const ModelLayout& at, uint32_t mesh, uint32_t firstInstance) {
  const std::span<const GpuMesh> meshes = at.model.meshes();
  const uint32_t instanceCount = static_cast<uint32_t>(memberScratch_.size());
  bool anyActive = false;
  for (size_t k = 0; k < memberScratch_.size(); ++k) anyActive |= rangeScratch_[k * meshes.size() + mesh].count > 0;
  for (uint32_t p = 0; p < meshes[mesh].primitives.size(); ++p) {
    const GpuPrimitive& prim = meshes[mesh].primitives[p];
    const bool morphs = anyActive && (prim.constants.flags & kDrawFlagMorphed) != 0;
    for (uint32_t runStart = 0; runStart < instanceCount;) {
      const bool mirrored = mirroredScratch_[firstInstance + runStart];
      uint32_t runEnd = runStart + 1;
      while (runEnd < instanceCount && mirroredScratch_[firstInstance + runEnd] == mirrored) ++runEnd;
      const uint32_t count = runEnd - runStart;
      slot.batches.push_back({&at.model, mesh, p, firstInstance + runStart, count, slot.capturedVertices, slot.morphedVec4s,
                              morphs, at.membersOffset + runStart});
      slot.batches.back().mirrored = mirrored;
      slot.batches.back().detailLayerMask = visibleDetailLayers(prim, firstInstance + runStart, count);
      if (at.mode == Mode::Capture) slot.capturedVertices += prim.vertexCount * count;
      // Room for every primitive with deltas, active or not: the buffer's
      // size then stays the same from frame to frame for the same instances.
      if ((prim.constants.flags & kDrawFlagMorphed) != 0)
        slot.morphedVec4s += prim.vertexCount * count * morphedVec4sPerVertex(prim);
      runStart = runEnd;
    }
  }
}

// Copies the laid-out frame into the slot's mapped buffers (grown first
// where it no longer fits) and records its stats.
Result<void> SceneRenderer::upload(Slot& slot, Mode mode) {
  ENG_TRY(ensureCapacity(slot, slot.instances, instanceScratch_.size() * sizeof(GpuInstance),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "instances"));
  ENG_TRY(ensureCapacity(slot, slot.active, activeScratch_.size() * sizeof(ActiveWeight),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "active weights"));
  ENG_TRY(ensureCapacity(slot, slot.joints, jointScratch_.size() * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         MemoryUsage::Upload, "joint matrices"));
  ENG_TRY(ensureCapacity(slot, slot.materials, materialScratch_.size() * sizeof(InstanceMaterial),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload, "instance materials"));
  ENG_TRY(ensureCapacity(slot, slot.weights, weightScratch_.size() * sizeof(float),
                         VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, MemoryUsage::Upload, "target weights"));
  ENG_TRY(ensureCapacity(slot, slot.morphed, VkDeviceSize{slot.morphedVec4s} * sizeof(glm::vec4),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "morphed vertices"));
  if (mode == Mode::Capture)
    ENG_TRY(ensureCapacity(slot, slot.capture, VkDeviceSize{slot.capturedVertices} * sizeof(GpuCapturedVertex),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "morph capture"));
  slot.stats = {static_cast<uint32_t>(slot.batches.size()), static_cast<uint32_t>(instanceScratch_.size()),
                static_cast<uint32_t>(activeScratch_.size()), static_cast<uint32_t>(jointScratch_.size()),
                static_cast<uint32_t>(materialScratch_.size()), static_cast<uint32_t>(weightScratch_.size()),
                uint64_t{slot.morphedVec4s} * sizeof(glm::vec4)};
  if (!instanceScratch_.empty())
    std::memcpy(slot.instances.mapped(), instanceScratch_.data(), instanceScratch_.size() * sizeof(GpuInstance));
  if (!activeScratch_.empty())
    std::memcpy(slot.active.mapped(), activeScratch_.data(), activeScratch_.size() * sizeof(ActiveWeight));
  if (!jointScratch_.empty())
    std::memcpy(slot.joints.mapped(), jointScratch_.data(), jointScratch_.size() * sizeof(glm::mat4));
  if (!weightScratch_.empty())
    std::memcpy(slot.weights.mapped(), weightScratch_.data(), weightScratch_.size() * sizeof(float));
  if (!materialScratch_.empty())
    std::memcpy(slot.materials.mapped(), materialScratch_.data(), materialScratch_.size() * sizeof(InstanceMaterial));
  return {};
}

void SceneRenderer::pickLevelsOfDetail(Slot& slot, const FrameGlobals& globals,
                                       std::span<const ModelInstance> instances, const LodPolicy& lod) const {
  // Pixels per unit of view-space size at depth 1.
  const float pixelsAtUnitDepth = std::abs(globals.proj[1][1]) * 0.5f * float(lod.viewHeight);  // Vulkan flips y
  for (Batch& batch : slot.batches) {
    const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
    batch.lod = 0;
    batch.shadowLod = 0;
    // With levels of detail (a window) the parts inside the head cast no
    // shadow: theirs falls into the eye sockets and the mouth, already dark
    // (the head's shadow, the baked occlusion), and the eyes and teeth are
    // 14k of the built-in head's triangles. Headless renders keep them.
    // A blended surface (an eye highlight, a tear line) lets the light through.
    batch.castsShadow = !(lod.maxPixelError > 0.0f && prim.insideTheHead) &&
                        (prim.constants.flags & kDrawFlagAlphaBlend) == 0;
    if (!prim.lods.empty()) {
      // The nearest instance decides: its model's bounding sphere's nearest
      // depth, and the largest scale of its primitive's transform.
      const Aabb& bounds = batch.model->bounds();
      float pixelsPerUnit = 0.0f;
      float largestScale = 0.0f;
      for (uint32_t k = 0; k < batch.instanceCount; ++k) {
        const glm::mat4& placed = instances[slot.members[batch.membersOffset + k]].transform;
        const glm::mat4& drawn = instanceScratch_[batch.firstInstance + k].model;
        const float placedScale = std::max({glm::length(glm::vec3(placed[0])), glm::length(glm::vec3(placed[1])),
                                            glm::length(glm::vec3(placed[2]))});
        const float drawnScale = std::max({glm::length(glm::vec3(drawn[0])), glm::length(glm::vec3(drawn[1])),
                                           glm::length(glm::vec3(drawn[2]))});
        largestScale = std::max(largestScale, drawnScale);
        const glm::vec3 centre = glm::vec3(placed * glm::vec4(bounds.center(), 1.0f));
        const float depth = -(globals.view * glm::vec4(centre, 1.0f)).z - 0.5f * bounds.diagonal() * placedScale;
        // Closer than a hundredth of the model (or around the camera): full detail.
        if (depth <= 0.01f * bounds.diagonal() * placedScale) {
          pixelsPerUnit = std::numeric_limits<float>::infinity();
          continue;  // (still for largestScale)
        }
        pixelsPerUnit = std::max(pixelsPerUnit, drawnScale * pixelsAtUnitDepth / depth);
      }
      for (size_t level = 0; lod.maxPixelError > 0.0f && pixelsAtUnitDepth > 0.0f && level < prim.lods.size(); ++level) {
        if (prim.lods[level].error * pixelsPerUnit > lod.maxPixelError) break;
        batch.lod = static_cast<uint32_t>(level + 1);
      }
      // The shadow map's casters, in every render (the view's own level or
      // not): the coarsest level that strays no further than the receiver's
      // push along its normal (lighting.glsl), so a coarser surface cannot
      // shadow the fine one it stands for, and the shadow's outline moves by
      // less than that -- well inside the filtered penumbra. Never finer than
      // the view's level.
      batch.shadowLod = batch.lod;
      const float receiverOffset = globals.shadow.z;
      for (size_t level = batch.lod; level < prim.lods.size(); ++level) {
        if (!(prim.lods[level].error * largestScale <= receiverOffset)) break;
        batch.shadowLod = static_cast<uint32_t>(level + 1);
      }
    }
    const uint32_t indexCount = batch.lod == 0 ? prim.indexCount : prim.lods[batch.lod - 1].indexCount;
    slot.stats.triangles += uint64_t{indexCount / 3} * batch.instanceCount;
    slot.stats.coarserDraws += batch.lod > 0 ? 1u : 0u;
  }
}

void SceneRenderer::orderDraws(Slot& slot, const FrameGlobals& globals) {
  slot.drawOrder.clear();
  blendScratch_.clear();
  for (uint32_t b = 0; b < slot.batches.size(); ++b) {
    const Batch& batch = slot.batches[b];
    const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
    if ((prim.constants.flags & kDrawFlagAlphaBlend) == 0) {
      slot.drawOrder.push_back(b);
      continue;
    }
    // Blended draws after every opaque one, farthest first, so each blends
    // over what is behind it; the depth of the batch's first instance (a
    // draw's instances share one order).
    const glm::mat4& placed = instanceScratch_[batch.firstInstance].model;
    const float depth = -(globals.view * placed * glm::vec4(prim.centre, 1.0f)).z;
    blendScratch_.push_back({depth, b});
  }
  std::stable_sort(blendScratch_.begin(), blendScratch_.end(),
                   [](const BlendDraw& a, const BlendDraw& b) { return a.depth > b.depth; });
  for (const BlendDraw& d : blendScratch_) slot.drawOrder.push_back(d.batch);
}

Result<void> SceneRenderer::prepare(uint32_t slot, const FrameGlobals& globals,
                                    std::span<const ModelInstance> instances, const LodPolicy& lod) {
  ENG_TRY(build(slot, instances, Mode::Draw));
  pickLevelsOfDetail(slots_[slot], globals, instances, lod);
  orderDraws(slots_[slot], globals);
  FrameGlobals written = globals;
  if (qualitySettings(quality_).shadowMapSize == 0) written.shadow.w = 0.0f;  // the tier has no shadow pass
  std::memcpy(slots_[slot].globals.mapped(), &written, sizeof(FrameGlobals));
  slots_[slot].contentKey = keyContent(slots_[slot], written);
  return {};
}

uint64_t SceneRenderer::keyContent(const Slot& slot, const FrameGlobals& written) const {
  Fnv1a key;
  key.addValue(written);
  key.addValue(pipelineGeneration_);
  key.addValues(std::span<const GpuInstance>(instanceScratch_));
  key.addValues(std::span<const float>(weightScratch_));
  key.addValues(std::span<const glm::mat4>(jointScratch_));
  key.addValues(std::span<const InstanceMaterial>(materialScratch_));
  for (const Batch& b : slot.batches) {
    // Not the levels of detail: they follow the view's size, which the caller
    // keys itself (a window's still view is drawn again at full resolution).
    const std::array<uint64_t, 7> drawn{b.model->uploadSerial(), b.mesh, b.primitive, b.firstInstance, b.instanceCount,
                                        b.detailLayerMask, uint64_t{b.castsShadow} << 1 | uint64_t{b.mirrored}};
    key.addValues(std::span<const uint64_t>(drawn));
  }
  return key.h;
}

Result<void> SceneRenderer::prepareCapture(uint32_t slot, std::span<const ModelInstance> instances) {
  if (!canCapture())
    return makeError(ErrorKind::Device, "morph capture needs vertexPipelineStoresAndAtomics, which " + ctx_->deviceInfo().name +
                     " does not support");
  return build(slot, instances, Mode::Capture);
}

uint32_t SceneRenderer::visibleDetailLayers(const GpuPrimitive& prim, uint32_t firstInstance,
                                            uint32_t instanceCount) const {
  // mesh.frag blends layer l where clamp(weight * strength, 0, 1) > 0, with the
  // weight as written to the weights buffer (zero below the active
  // threshold): a layer whose weight or strength is zero for every member
  // cannot show. Any other may (the shader still tests each instance's).
  const size_t layers = std::min<size_t>({prim.constants.detailLayerCount, prim.detailLayers.size(), 32});
  uint32_t mask = 0;
  for (size_t l = 0; l < layers; ++l) {
    const GpuDetailLayer& layer = prim.detailLayers[l];
    if (layer.strength == 0.0f || layer.target == UINT32_MAX) continue;
    for (uint32_t k = 0; k < instanceCount; ++k) {
      const size_t weight = size_t{instanceScratch_[firstInstance + k].weightOffset} + layer.target;
      if (weight < weightScratch_.size() && weightScratch_[weight] != 0.0f) {
        mask |= 1u << l;
        break;
      }
    }
  }
  return mask;
}

FrameStats SceneRenderer::stats(uint32_t slot) const { return slot < slots_.size() ? slots_[slot].stats : FrameStats{}; }

void SceneRenderer::bindPrimitive(VkCommandBuffer cmd, const Batch& batch, DrawConstants& constants) const {
  const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
  const VkBuffer vertices = batch.model->vertexBuffer();
  const std::array<VkBuffer, 5> buffers{vertices, vertices, vertices, vertices, vertices};
  const std::array<VkDeviceSize, 5> offsets{prim.positionOffset, prim.normalOffset, prim.texcoordOffset,
                                            prim.tangentOffset, prim.colorOffset};
  vkCmdBindVertexBuffers(cmd, 0, uint32_t(buffers.size()), buffers.data(), offsets.data());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts_->pipelineLayout(), 1, 1,
                          &prim.descriptorSet, 0, nullptr);
  constants = prim.constants;
  constants.firstInstance = batch.firstInstance;
  constants.captureOffset = batch.captureOffset;
  constants.morphOffset = batch.morphOffset;
  constants.detailLayerMask = batch.detailLayerMask;
  if (!batch.morphs) constants.flags &= ~kDrawFlagMorphed;  // every instance in the rest pose: nothing written
  if (batch.mirrored) constants.flags |= kDrawFlagMirrored;
}

void SceneRenderer::drawBatches(VkCommandBuffer cmd, const Slot& slot, DrawPass pass) const {
  const bool colourPass = pass != DrawPass::Shadow;
  VkPipeline bound = VK_NULL_HANDLE;
  for (const uint32_t b : slot.drawOrder) {
    const Batch& batch = slot.batches[b];
    const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
    const uint32_t flags = prim.constants.flags;
    const bool blended = (flags & kDrawFlagAlphaBlend) != 0;
    const bool drawn = pass == DrawPass::Shadow   ? batch.castsShadow
                       : pass == DrawPass::Opaque  ? !blended
                       : pass == DrawPass::Blended ? blended
                                                   : !blended && (flags & kDrawFlagToonOutline) != 0;
    if (!drawn) continue;
    const AlphaPipeline alpha = blended                             ? AlphaPipeline::Blend
                                : (flags & kDrawFlagAlphaMask) != 0 ? AlphaPipeline::Mask
                                                                    : AlphaPipeline::Opaque;
    const VkPipeline pipeline =
        pass == DrawPass::Shadow     ? pipelines_.shadow(alpha == AlphaPipeline::Mask)
        : pass == DrawPass::Outlines ? pipelines_.outline(batch.mirrored, alpha == AlphaPipeline::Mask)
                                     : pipelines_.mesh((flags & kDrawFlagDoubleSided) != 0, batch.mirrored, alpha);
    if (pipeline != bound) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
      bound = pipeline;
    }
    DrawConstants constants;
    bindPrimitive(cmd, batch, constants);
    vkCmdPushConstants(cmd, layouts_->pipelineLayout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(DrawConstants), &constants);
    // The shadow pass has its own level.
    const uint32_t level = colourPass ? batch.lod : batch.shadowLod;
    const bool full = level == 0;
    vkCmdBindIndexBuffer(cmd, batch.model->indexBuffer(), full ? prim.indexOffset : prim.lods[level - 1].indexOffset,
                         VK_INDEX_TYPE_UINT32);
    const std::vector<DetailRuns::Run>& runs = full ? prim.detailRuns : prim.lods[level - 1].detailRuns;
    if (colourPass && constants.detailLayerMask != 0 && !runs.empty()) {
      // Each run with only the layers that can show on it (most triangles: none).
      const uint32_t visible = constants.detailLayerMask;
      for (const DetailRuns::Run& run : runs) {
        constants.detailLayerMask = visible & run.layerMask;
        vkCmdPushConstants(cmd, layouts_->pipelineLayout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(DrawConstants), &constants);
        vkCmdDrawIndexed(cmd, run.indexCount, batch.instanceCount, run.firstIndex, 0, batch.firstInstance);
      }
      continue;
    }
    vkCmdDrawIndexed(cmd, full ? prim.indexCount : prim.lods[level - 1].indexCount, batch.instanceCount, 0, 0,
                     batch.firstInstance);
  }
}

void SceneRenderer::recordMorphPass(VkCommandBuffer cmd, uint32_t slotIndex) const {
  const Slot& slot = slots_[slotIndex];
  if (std::none_of(slot.batches.begin(), slot.batches.end(), [](const Batch& b) { return b.morphs; })) return;
  const VkPipelineLayout layout = layouts_->morphPipelineLayout();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_.morph());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &slot.descriptorSet, 0, nullptr);
  const uint32_t maxGroups = ctx_->deviceInfo().properties.limits.maxComputeWorkGroupCount[0];
  // A CPU device pays a fixed cost per invocation (an empty 50k-invocation
  // dispatch takes 0.6 ms on lavapipe): there each invocation morphs two
  // vertices, 10-16 % faster from 5k to 50k vertices. A GPU's invocations are
  // cheap and its parallelism is not, so it keeps one vertex each.
  const uint32_t verticesPerInvocation = ctx_->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 2u : 1u;
  for (const Batch& batch : slot.batches) {
    if (!batch.morphs) continue;
    const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 1, 1, &prim.descriptorSet, 0, nullptr);
    DrawConstants constants = prim.constants;
    constants.firstInstance = batch.firstInstance;
    constants.morphOffset = batch.morphOffset;
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(DrawConstants), &constants);
    // kMorphGroupSize invocations per group, each morphing verticesPerInvocation
    // vertices (morph.comp strides over the primitive; a huge one loops).
    const uint32_t perGroup = kMorphGroupSize * verticesPerInvocation;
    const uint32_t groups = std::min((prim.vertexCount + perGroup - 1) / perGroup, maxGroups);
    vkCmdDispatch(cmd, groups, batch.instanceCount, 1);
  }
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, 0, 1, &barrier,
                       0, nullptr, 0, nullptr);
}

void SceneRenderer::recordShadowPass(VkCommandBuffer cmd, uint32_t slotIndex) const {
  const Slot& slot = slots_[slotIndex];
  recordMorphPass(cmd, slotIndex);
  shadowMap_.begin(cmd);
  if (qualitySettings(quality_).shadowMapSize > 0) {  // else the pass only clears the token map
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts_->pipelineLayout(), 0, 1,
                            &slot.descriptorSet, 0, nullptr);
    drawBatches(cmd, slot, DrawPass::Shadow);
  }
  shadowMap_.end(cmd);
}

void SceneRenderer::record(VkCommandBuffer cmd, uint32_t slotIndex, VkExtent2D extent, bool drawBackdrop) const {
  const Slot& slot = slots_[slotIndex];
  const VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts_->pipelineLayout(), 0, 1,
                          &slot.descriptorSet, 0, nullptr);
  // Outlines after the opaque draws they surround and before the blended
  // ones, which do not write depth and would otherwise be drawn over. The
  // backdrop between them: behind the opaque draws (early depth rejects the
  // pixels they cover), under the blended ones.
  drawBatches(cmd, slot, DrawPass::Opaque);
  drawBatches(cmd, slot, DrawPass::Outlines);
  if (drawBackdrop) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.background());
    vkCmdDraw(cmd, 3, 1, 0, 0);
  }
  drawBatches(cmd, slot, DrawPass::Blended);
}

void SceneRenderer::recordCapture(VkCommandBuffer cmd, uint32_t slotIndex) const {
  const Slot& slot = slots_[slotIndex];
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layouts_->pipelineLayout(), 0, 1,
                          &slot.descriptorSet, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.capture());
  for (const Batch& batch : slot.batches) {
    const GpuPrimitive& prim = batch.model->meshes()[batch.mesh].primitives[batch.primitive];
    DrawConstants constants;
    bindPrimitive(cmd, batch, constants);
    vkCmdPushConstants(cmd, layouts_->pipelineLayout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(DrawConstants), &constants);
    // Non-indexed points: every vertex runs exactly once per instance.
    vkCmdDraw(cmd, prim.vertexCount, batch.instanceCount, 0, batch.firstInstance);
  }
}

void SceneRenderer::recordCaptureReadBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

std::vector<CapturedPrimitive> SceneRenderer::readCapture(uint32_t slotIndex) const {
  const Slot& slot = slots_[slotIndex];
  std::vector<CapturedPrimitive> out;
  if (!slot.capture) return out;
  const auto* captured = reinterpret_cast<const GpuCapturedVertex*>(slot.capture.mapped());
  for (const Batch& batch : slot.batches) {
    const uint32_t n = batch.model->meshes()[batch.mesh].primitives[batch.primitive].vertexCount;
    for (uint32_t k = 0; k < batch.instanceCount; ++k) {
      CapturedPrimitive& c = out.emplace_back();
      c.instance = slot.members[batch.membersOffset + k];
      c.mesh = static_cast<int>(batch.mesh);
      c.primitive = static_cast<int>(batch.primitive);
      c.positions.resize(n);
      c.normals.resize(n);
      c.tangents.resize(n);
      const GpuCapturedVertex* src = captured + batch.captureOffset + size_t{k} * n;
      for (uint32_t v = 0; v < n; ++v) {
        c.positions[v] = glm::vec3(src[v].position);
        c.normals[v] = glm::vec3(src[v].normal);
        c.tangents[v] = src[v].tangent;
      }
    }
  }
  return out;
}

bool SceneRenderer::refreshPipelines() {
  if (shaders_->generation() == pipelineGeneration_) return false;
  pipelineGeneration_ = shaders_->generation();
  auto rebuilt = ScenePipelines::create(*ctx_, *layouts_, *shaders_, renderPass_, samples_, shadowMap_.renderPass(),
                                        qualitySettings(quality_));
  if (!rebuilt) {
    logError("shader hot reload: pipelines not rebuilt, keeping the previous ones: " + rebuilt.error().message);
    return false;
  }
  vkDeviceWaitIdle(ctx_->device());  // the old pipelines may still be in flight
  pipelines_ = std::move(rebuilt).value();
  return true;
}

}  // namespace eng::vk
