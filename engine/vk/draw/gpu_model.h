#pragma once
// A Model uploaded for drawing: one vertex buffer, one index buffer, one
// storage buffer of sparse morph deltas (layout in engine/shaders/morph.glsl), one
// of joint influences (skin.glsl), textures, and one descriptor set per
// primitive; the skins and the node hierarchy's rest pose stay on the CPU to
// make each frame's joint matrices. Immutable once created;
// any number of instances with their own weights draw from it.
//
// Lifetime: must not outlive the Context and SceneLayouts it was created with.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/scene/detail_regions.h"
#include "engine/scene/model.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/vk/device/buffer.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/gpu_types.h"
#include "engine/vk/device/gpu_image.h"
#include "engine/vk/draw/scene_layouts.h"
#include "engine/view/scene_mesh_nodes.h"

namespace eng::vk {

// A coarser level of detail of a primitive (eng::buildLodChain): a range of
// GpuModel::indexBuffer() over the same vertices.
struct GpuLod {
  VkDeviceSize indexOffset = 0;
  uint32_t indexCount = 0;
  float error = 0.0f;  // how far it may stray from the full mesh, model units
  std::vector<DetailRuns::Run> detailRuns;  // as GpuPrimitive::detailRuns, for this level's indices
};

struct GpuPrimitive {
  uint32_t vertexCount = 0;
  uint32_t indexCount = 0;
  // Byte offsets of the attribute arrays in GpuModel::vertexBuffer().
  VkDeviceSize positionOffset = 0;
  VkDeviceSize normalOffset = 0;
  VkDeviceSize texcoordOffset = 0;   // zeros when the primitive has no texcoords
  VkDeviceSize tangentOffset = 0;    // zeros when the primitive has no tangents
  VkDeviceSize colorOffset = 0;      // ones (white) when the primitive has no vertex colours
  VkDeviceSize indexOffset = 0;      // in GpuModel::indexBuffer(), uint32 indices
  std::vector<GpuLod> lods;          // coarser levels, finest first (empty: small or unsimplifiable)
  DrawConstants constants;           // material, flags and vertexCount; instance fields left 0
  // The material's detail layers (target among the mesh's targets, strength),
  // as the fragment shader reads them: the scene renderer picks the ones an
  // instance's weights can show. Only the first constants.detailLayerCount are drawn.
  std::vector<GpuDetailLayer> detailLayers;
  // With detail layers (opaque primitives): the index list in runs of
  // triangles the same layers can reach (eng::DetailRegions), drawn one run
  // at a time with only those layers; empty: one draw with every layer.
  std::vector<DetailRuns::Run> detailRuns;
  // Inside the head (engine/scene/inner_face_parts.h: eyeball, teeth, tongue, mouth interior):
  // a window's shadow pass leaves it out.
  bool insideTheHead = false;
  glm::vec3 centre{0.0f};  // of the rest positions' bounds, in mesh space: blended draws are sorted by its depth
  VkDescriptorSet descriptorSet = VK_NULL_HANDLE;  // set 1
};

struct GpuMesh {
  std::string name;
  uint32_t targetCount = 0;
  uint32_t weightOffset = 0;  // first weight of this mesh in the model's flat weight vector
  std::vector<GpuPrimitive> primitives;
};

struct PrimitiveRanges;  // gpu_model.cpp: where create() staged one primitive's data
class ByteBlob;

// The CPU half of an upload: every primitive's vertex arrays, levels of
// detail, detail-layer runs, sparse deltas and joint influences laid out as
// the device buffers hold them. Made once, it uploads to any number of
// devices whose limits it fits (GpuModel::create), e.g. a sequence's device
// lanes, without simplifying the meshes again.
class GpuModelStaging {
 public:
  // Checks the model (eng::checkModel with ModelCheck::gpuUpload()); errors
  // name the model file, then the mesh and primitive. `limits`: the devices'
  // (storage and texel offset alignments, texel buffer size).
  static Result<GpuModelStaging> build(const Model& model, const VkPhysicalDeviceLimits& limits);
  // Whether a device with `limits` can take it (the alignments it was laid out with, its texel buffers).
  Result<void> fits(const VkPhysicalDeviceLimits& limits) const;

  GpuModelStaging();
  GpuModelStaging(GpuModelStaging&&) noexcept;
  GpuModelStaging& operator=(GpuModelStaging&&) noexcept;
  ~GpuModelStaging();

 private:
  friend class GpuModel;
  struct Blobs;
  std::unique_ptr<Blobs> blobs_;
  std::vector<GpuMesh> meshes_;  // descriptor sets still null
  std::vector<std::vector<PrimitiveRanges>> ranges_;  // by mesh, then primitive
  VkDeviceSize storageAlign_ = 16;
  size_t largestTexelBuffer_ = 0;  // elements
};

class GpuModel {
 public:
  // Checks the model first (eng::checkModel with ModelCheck::gpuUpload());
  // errors name the model file, then the mesh and primitive. Draws the model
  // as given: a face to be shown dressed (procedural eyes, skin tone, brows,
  // occlusion) is dressed by its loader first (importers/face_dressing.h).
  static Result<GpuModel> create(const Context& ctx, const SceneLayouts& layouts, const Model& model);
  // The same from a staging built from `model` (GpuModelStaging::build) for
  // devices with this one's limits.
  static Result<GpuModel> create(const Context& ctx, const SceneLayouts& layouts, const Model& model,
                                 const GpuModelStaging& staging);

  const std::string& name() const { return name_; }
  // Unique per upload in this process (kept by moves): a new upload of
  // changed content at the same address is still another model.
  uint64_t uploadSerial() const { return uploadSerial_; }
  std::span<const GpuMesh> meshes() const { return meshes_; }
  std::span<const MeshNode> meshNodes() const { return meshNodes_; }
  // Materials an instance may override (ModelInstance::materials): those of
  // the model, by index.
  uint32_t materialCount() const { return materialCount_; }
  // Every material's own parameters as drawn: materialCount() records, then
  // the default material of primitives without one (GpuPrimitive::constants.material indexes this list).
  std::span<const InstanceMaterial> materials() const { return materials_; }
  // Length of the model's flat weight vector (eng::WeightLayout(model).total()).
  uint32_t weightCount() const { return weightCount_; }
  const Aabb& bounds() const { return bounds_; }
  // Nodes of the source model: the length of a pose's world matrices.
  uint32_t nodeCount() const { return static_cast<uint32_t>(restWorld_.size()); }
  // Model-space matrix of every node in the rest (bind) pose.
  std::span<const glm::mat4> restWorld() const { return restWorld_; }
  // The joint matrices of a skinned mesh node (node.skin >= 0) for the node
  // world matrices `world` (nodeCount() long, or empty for the rest pose).
  void jointMatrices(const MeshNode& node, std::span<const glm::mat4> world, std::vector<glm::mat4>& out) const;
  VkBuffer vertexBuffer() const { return vertices_.handle(); }
  // Device memory held in buffers (vertices, indices, morph deltas, detail
  // layers, skin influences); textures not included.
  VkDeviceSize bufferBytes() const {
    return vertices_.size() + indices_.size() + deltas_.size() + detailLayers_.size() + skinInfluences_.size();
  }
  VkBuffer indexBuffer() const { return indices_.handle(); }

 private:
  // The morph pre-pass's texel buffers of one primitive (set 1 bindings 0-2).
  struct MorphInputViews {
    VkBufferView offsets, entries, rest;
  };
  // The steps of create(), in order.
  Result<void> uploadBuffers(const Context& ctx, const GpuModelStaging& staging);
  Result<void> uploadTextures(const Context& ctx, const Model& model);
  Result<void> createDescriptorSets(const Context& ctx, const SceneLayouts& layouts, const Model& model,
                                    const GpuModelStaging& staging);
  void writePrimitiveSet(const Context& ctx, const SceneLayouts& layouts, const Model& model, const Primitive& prim,
                         const PrimitiveRanges& ranges, const MorphInputViews& morph, GpuPrimitive& gp) const;

  std::string name_;
  uint64_t uploadSerial_ = 0;
  std::vector<GpuMesh> meshes_;
  std::vector<MeshNode> meshNodes_;
  uint32_t weightCount_ = 0;
  uint32_t materialCount_ = 0;
  std::vector<InstanceMaterial> materials_;
  Aabb bounds_;
  Buffer vertices_;
  Buffer indices_;
  Buffer deltas_;
  Buffer detailLayers_;
  Buffer skinInfluences_;
  std::vector<Skin> skins_;
  std::vector<glm::mat4> restWorld_;
  std::vector<GpuImage> textures_;      // by Model image index, sRGB; empty where unused as colour
  std::vector<GpuImage> dataTextures_;  // the same, linear: metallic-roughness, normal, occlusion images
  std::vector<GpuImage> detailArrays_;  // by material index; empty where it has no layers
  // The samplings materials' textures ask for other than the default (SceneLayouts::sampler()).
  std::vector<std::pair<TextureSampling, UniqueSampler>> samplers_;
  std::vector<UniqueBufferView> texelViews_;  // the morph pre-pass's inputs of the primitives with deltas
  UniqueDescriptorPool descriptorPool_;
};

// A material's own parameters, as an instance draws it when nothing moves
// them (a per-instance record, e.g. VRM material binds, starts from this).
InstanceMaterial instanceMaterial(const Material& mat);

}  // namespace eng::vk
