#pragma once
// Draws model instances into a render pass of any target. Per frame the CPU
// writes only the instance records (transform + slice of the active list +
// slice of the joint matrices + first material record), the compact
// active-weight list, every instance's target weights, the joint matrices of skinned mesh nodes and one
// material record per material per instance (48 bytes: base colour, emission,
// UV transform; an animation's overrides or the model's own values), all into
// persistent mapped buffers (descriptors are rewritten only when one grows);
// each mesh of a model draws ALL instances of that model in one instanced
// draw per primitive. Morphing runs once per frame, before the shadow pass:
// a compute pre-pass (engine/shaders/morph.comp) writes every morphed
// primitive's vertices for every instance into the slot's morphed-vertex
// buffer, which the shadow, main and capture passes read.
//
// Frame slots: the caller owns synchronisation; prepare(slot) may only be
// called once the GPU has finished the previous commands recorded for that slot.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/gpu_model.h"
#include "engine/vk/draw/gpu_types.h"
#include "engine/vk/draw/render_quality.h"
#include "engine/vk/draw/scene_layouts.h"
#include "engine/vk/draw/scene_pipelines.h"
#include "engine/vk/device/shader_library.h"
#include "engine/vk/draw/shadow_map.h"

namespace eng::vk {

struct ModelInstance {
  const GpuModel* model = nullptr;
  glm::mat4 transform{1.0f};
  // The model's flat weight vector (eng::WeightLayout order), model->weightCount() long.
  std::span<const float> weights;
  // The instance's skeleton pose: every node's model-space matrix
  // (eng::poseWorldMatrices), model->nodeCount() long; empty = the rest
  // (bind) pose. Moves skinned meshes through their joints and rigid mesh nodes.
  std::span<const glm::mat4> nodeWorld;
  // The instance's material parameters, by material index, at most
  // model->materialCount() long: what an animation moves (VRM material colour
  // and texture transform binds). Materials past the end (or all, when empty)
  // keep the model's own values (model->materials()).
  std::span<const InstanceMaterial> materials;
};

// Morphed (then skinned) vertices of one primitive of one instance, in the
// space of the mesh's node (the first scene node drawing the mesh supplies
// the skin and the pose's joint matrices).
struct CapturedPrimitive {
  size_t instance = 0;  // index into the instances given to prepareCapture
  int mesh = -1;
  int primitive = -1;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;  // xyz morphed + renormalised, w = handedness (zeros without tangents)
};

// What the last prepare() of a slot laid out (for tests, overlays, benchmarks).
struct FrameStats {
  uint32_t draws = 0;          // instanced draw calls, one per (mesh node, primitive)
  uint32_t instances = 0;      // GPU instance records
  uint32_t activeWeights = 0;  // entries of the active list uploaded this frame
  uint32_t jointMatrices = 0;  // joint matrices uploaded this frame
  uint32_t materials = 0;      // instance material records uploaded this frame
  uint32_t targetWeights = 0;  // weights uploaded for the morph pre-pass (every target of every instance)
  uint64_t morphedBytes = 0;   // the morph pre-pass's output buffer: room for every morphed instance vertex
  uint64_t triangles = 0;      // triangles drawn (every instance, at the levels of detail picked)
  uint32_t coarserDraws = 0;   // draws at a coarser level of detail than the full mesh
};

// Which level of detail (GpuPrimitive::lods) a frame draws: per draw, the
// coarsest level whose error, projected at its nearest instance, stays within
// maxPixelError pixels of a view viewHeight pixels tall. The default draws
// every triangle (headless renders, goldens, captures).
struct LodPolicy {
  float maxPixelError = 0.0f;  // 0: always the full mesh
  uint32_t viewHeight = 0;     // pixels
};

class SceneRenderer {
 public:
  // `layouts` and `shaders` must outlive the renderer.
  static Result<SceneRenderer> create(const Context& ctx, const SceneLayouts& layouts, const ShaderLibrary& shaders,
                                      VkRenderPass renderPass, VkSampleCountFlagBits samples,
                                      uint32_t frameSlots, RenderQuality quality = RenderQuality::High);
  RenderQuality quality() const { return quality_; }

  // Writes slot's frame data. Errors (naming the instance and mesh): null
  // model, wrong number of weights, non-finite weight, pose of the wrong size,
  // more materials than the model has, a non-finite material value.
  Result<void> prepare(uint32_t slot, const FrameGlobals& globals, std::span<const ModelInstance> instances,
                       const LodPolicy& lod = {});
  FrameStats stats(uint32_t slot) const;
  // A key of everything slot's last prepare() would draw (frame globals,
  // instance records, weights, joints, materials, models, pipelines) but the
  // levels of detail: equal keys at one view size draw the same picture, so
  // a window can re-present its last 3D view instead of drawing it again.
  uint64_t contentKey(uint32_t slot) const { return slot < slots_.size() ? slots_[slot].contentKey : 0; }
  // Before the scene's render pass: the morph pre-pass (recordMorphPass),
  // then the key light's shadow map for the prepared draws.
  void recordShadowPass(VkCommandBuffer cmd, uint32_t slot) const;
  // Outside any render pass: morphs every prepared (instance, primitive) with
  // active weights once, then a barrier makes the result visible to the
  // vertex shaders. recordShadowPass calls it; call it directly only before
  // recordCapture, or to time the morph alone.
  void recordMorphPass(VkCommandBuffer cmd, uint32_t slot) const;
  // Inside the render pass: background, then every prepared draw.
  // drawBackdrop: false leaves the cleared colour (a solid or transparent backdrop).
  void record(VkCommandBuffer cmd, uint32_t slot, VkExtent2D extent, bool drawBackdrop = true) const;

  // Morph capture (tests, tools): prepare, recordMorphPass before the render pass, record inside it,
  // then the barrier after it, submit, wait, and read.
  bool canCapture() const { return pipelines_.capture() != VK_NULL_HANDLE; }
  Result<void> prepareCapture(uint32_t slot, std::span<const ModelInstance> instances);
  void recordCapture(VkCommandBuffer cmd, uint32_t slot) const;
  static void recordCaptureReadBarrier(VkCommandBuffer cmd);
  std::vector<CapturedPrimitive> readCapture(uint32_t slot) const;

  // When the shader library holds newer SPIR-V than the pipelines, rebuilds
  // them (after vkDeviceWaitIdle). On failure logs and keeps the old ones.
  // Returns true when pipelines were replaced.
  bool refreshPipelines();

 private:
  enum class Mode { Draw, Capture };
  // One primitive drawn for `instanceCount` instances from `firstInstance`.
  struct Batch {
    const GpuModel* model = nullptr;
    uint32_t mesh = 0;
    uint32_t primitive = 0;
    uint32_t firstInstance = 0;
    uint32_t instanceCount = 0;
    uint32_t captureOffset = 0;  // first captured vertex slot (capture mode)
    uint32_t morphOffset = 0;    // first vec4 of the batch's morphed vertices
    bool morphs = false;         // the primitive has deltas and some instance has active weights
    uint32_t membersOffset = 0;  // into Slot::members: the caller's instance indices
    uint32_t lod = 0;            // 0: the full mesh; k: GpuPrimitive::lods[k - 1]
    uint32_t shadowLod = 0;      // the same for the shadow pass (as coarse as lod or coarser)
    bool castsShadow = true;     // false: left out of the shadow pass (a part inside the head, in a window)
    uint32_t detailLayerMask = 0;  // DrawConstants::detailLayerMask: layers some member's weights show
    bool mirrored = false;       // every instance's transform has a negative determinant (kDrawFlagMirrored)
  };
  struct Slot {
    Buffer globals;
    Buffer instances;
    Buffer active;
    Buffer joints;
    Buffer materials;
    Buffer capture;
    Buffer weights;  // every instance's target weights, zero where inactive (morph.glsl)
    UniqueBufferView weightTexels;  // `weights` as the morph pre-pass reads it
    Buffer morphed;  // per (morphed batch, instance, vertex) two or three vec4 (morph.glsl)
    VkDescriptorSet descriptorSet = VK_NULL_HANDLE;
    std::vector<Batch> batches;
    std::vector<uint32_t> drawOrder;  // into batches: opaque and masked in order, then blended far to near
    std::vector<uint32_t> members;
    uint32_t capturedVertices = 0;
    uint32_t morphedVec4s = 0;
    FrameStats stats;
    uint64_t contentKey = 0;
  };

  // Lays out the instances' frame data in the slot: the steps below, in order.
  Result<void> build(uint32_t slot, std::span<const ModelInstance> instances, Mode mode);
  // The model whose instances (memberScratch_) build() is laying out.
  struct ModelLayout {
    const GpuModel& model;
    std::span<const ModelInstance> instances;  // all of the caller's
    Mode mode;
    uint32_t membersOffset;  // where the members start in Slot::members
  };
  struct JointSet;
  void clearLayout(Slot& slot);
  Result<void> checkInstances(std::span<const ModelInstance> instances);
  uint32_t gatherMembers(Slot& slot, const GpuModel& model, std::span<const ModelInstance> instances);
  void layOutMaterials(const ModelLayout& at);
  void layOutWeights(const ModelLayout& at);
  Result<void> listActiveWeights(const ModelLayout& at);
  void addMeshBatches(Slot& slot, const ModelLayout& at, uint32_t mesh, const MeshNode* node);
  void addInstanceRecord(const ModelLayout& at, size_t member, uint32_t mesh, const MeshNode* node);
  const JointSet& memberJoints(const ModelLayout& at, size_t member, const MeshNode& node);
  void addPrimitiveBatches(Slot& slot, const ModelLayout& at, uint32_t mesh, uint32_t firstInstance);
  Result<void> upload(Slot& slot, Mode mode);
  // DrawConstants::detailLayerMask of a batch of `prim` whose instance records
  // (already in instanceScratch_, weights in weightScratch_) start at firstInstance.
  uint32_t visibleDetailLayers(const GpuPrimitive& prim, uint32_t firstInstance, uint32_t instanceCount) const;
  // Sets every batch's levels of detail (Batch::lod, shadowLod), whether it
  // casts a shadow, and the triangle counts of the slot's stats.
  void pickLevelsOfDetail(Slot& slot, const FrameGlobals& globals, std::span<const ModelInstance> instances,
                          const LodPolicy& lod) const;
  Result<void> ensureCapacity(Slot& slot, Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                              MemoryUsage memory, const char* name);
  // (Re)creates the weights' texel view and writes every binding of set 0.
  Result<void> writeDescriptors(Slot& slot) const;
  void bindPrimitive(VkCommandBuffer cmd, const Batch& batch, DrawConstants& constants) const;
  // Which of the slot's draws a drawBatches call records, and how.
  enum class DrawPass {
    Shadow,    // the shadow casters, depth only
    Opaque,    // every draw that is not blended (opaque and masked)
    Outlines,  // the MToon outlines of the opaque and masked toon draws
    Blended,   // the blended draws, far to near
  };
  void drawBatches(VkCommandBuffer cmd, const Slot& slot, DrawPass pass) const;
  // Fills slot.drawOrder (after build: reads instanceScratch_).
  void orderDraws(Slot& slot, const FrameGlobals& globals);
  // Slot::contentKey of the prepared slot drawn with `written` globals.
  uint64_t keyContent(const Slot& slot, const FrameGlobals& written) const;

  const Context* ctx_ = nullptr;
  const SceneLayouts* layouts_ = nullptr;
  const ShaderLibrary* shaders_ = nullptr;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
  RenderQuality quality_ = RenderQuality::High;
  uint64_t pipelineGeneration_ = 0;
  ShadowMap shadowMap_;
  ScenePipelines pipelines_;
  UniqueDescriptorPool descriptorPool_;
  std::vector<Slot> slots_;
  // Scratch reused every frame (capacity persists: no allocation in steady state).
  std::vector<GpuInstance> instanceScratch_;
  struct BlendDraw {
    float depth;
    uint32_t batch;
  };
  std::vector<BlendDraw> blendScratch_;
  std::vector<uint8_t> mirroredScratch_;  // per instanceScratch_ entry: its transform mirrors (winds clockwise)
  std::vector<ActiveWeight> activeScratch_;
  std::vector<float> weightScratch_;
  std::vector<uint32_t> weightOffsetScratch_;  // per member of the model being laid out
  std::vector<glm::mat4> jointScratch_;
  std::vector<glm::mat4> skinScratch_;
  // Per member of the model being built: the skin and mesh-node world its
  // joint matrices were last made for, and where they lie in jointScratch_.
  struct JointSet {
    int skin = -1;
    glm::mat4 meshWorld{0.0f};
    uint32_t offset = 0, count = 0;
  };
  std::vector<JointSet> jointSetScratch_;
  std::vector<InstanceMaterial> materialScratch_;
  std::vector<uint32_t> materialOffsetScratch_;  // per member of the model being laid out
  std::vector<const GpuModel*> modelScratch_;
  std::vector<uint32_t> memberScratch_;
  struct ActiveRange {
    uint32_t offset = 0;
    uint32_t count = 0;
  };
  std::vector<ActiveRange> rangeScratch_;  // per (member, mesh) of the model being laid out
};

}  // namespace eng::vk
