// glTF 2.0 / GLB: the loader (accessors, sparse, morph targets, skins,
// animations, KHR_mesh_quantization, EXT/KHR_meshopt_compression,
// KHR_draco_mesh_compression, EXT_texture_webp, KHR_texture_transform,
// embedded images), then what the runtime does with a loaded model: the
// structural check the writer relies on, skeletal poses of every animation,
// posed bounds with every target at full weight, the head joint, the weights
// animations as timelines and rig detection over the target names, and what
// the upload computes per primitive (crease darkening, parts inside the head).
// JSON inputs also grow under fuzz/json_growth.h's mutator (more nodes,
// targets, deeper hierarchies): with -timeout, a loader or pass whose work
// grows with the square of a count is a finding.
#include <cmath>

#include "engine/scene/crease_shading.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/inner_face_parts.h"
#include "engine/scene/model_check.h"
#include "engine/scene/posed_bounds.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/weights.h"
#include "bake/gltf_timeline.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "fuzz/fuzz_support.h"
#include "fuzz/json_growth.h"

namespace {

// Small enough that a hostile declared count is refused quickly instead of
// filling memory up to the 1 GiB default (libFuzzer's -rss_limit_mb is 2 GiB).
constexpr eng::GltfLoadLimits kLimits{.maxFileBytes = size_t{8} << 20,
                                      .maxDecodedBytes = size_t{64} << 20,
                                      .maxImagePixels = size_t{4} << 20};

void exercise(const eng::Model& model) {
  const auto consistent = eng::checkModel(model);
  FUZZ_PROPERTY(consistent.ok(), "loaded model fails checkModel: " + consistent.error().message);

  eng::Pose pose = eng::restPose(model);
  std::vector<glm::mat4> world;
  for (const eng::Animation& animation : model.animations) {
    for (float t : {0.0f, 0.37f, 1e6f}) eng::sampleAnimation(animation, t, pose);
    eng::poseWorldMatrices(model, pose, world);
  }
  const eng::WeightLayout layout(model);
  std::vector<float> full(layout.total(), 1.0f);
  (void)eng::posedBounds(model, pose, full);
  (void)eng::findHeadJoint(model);
  (void)eng::posedMorphedBounds(model, pose);
  (void)eng::restWorldMatrices(model);
  (void)eng::sceneMeshNodeIndices(model);
  (void)eng::partsInsideTheHead(model);
  for (const eng::Mesh& mesh : model.meshes)
    for (const eng::Primitive& prim : mesh.primitives) (void)eng::bakeCreaseDarkening(prim);
  (void)bake::importGltfTimelines(model);
  (void)facial::buildRigMapping(layout.names());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The loader detects GLB by its magic, so one name serves both forms.
  const auto path = fuzz::writeInput("input.gltf", data, size);
  auto model = eng::loadModel(path, kLimits);
  if (model) exercise(*model);
  return 0;
}

FUZZ_GROW_JSON_MUTATOR
