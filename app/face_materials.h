#pragma once
// The material parameters one face instance is drawn with this frame. A VRM
// face's expressions may bind materials: a colour bind moves a material's
// base colour (or emission) from its own value towards the bind's target by
// the expression weight, a texture transform bind its UV scale and offset,
// and the deltas of all weighted expressions add (VRMC_vrm 1.0 expressions,
// VRM 0.x materialValues; facial::VrmExpressionSet::applyMaterials). Every
// view (express, sheet, play, the demo, the editor) draws these as
// per-instance material records (eng::vk::ModelInstance::materials), so a
// colour follows the animated weights frame by frame without touching the
// uploaded model. Sized at creation; update() does not allocate.
//
//   auto materials = app::FaceMaterials::create(face);            // once per instance
//   driver.update(dt);
//   materials->update(driver.expressionWeights());                 // every frame
//   instance.materials = materials->materials();
#include <memory>
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "engine/vk/draw/gpu_types.h"
#include "facial/runtime/rig/vrm_expressions.h"

namespace app {

class FaceSetup;

class FaceMaterials {
 public:
  // Drives nothing: materials() stays empty (the model's own values are drawn).
  FaceMaterials() = default;
  // Drives the face's materials when it is a VRM whose expressions bind
  // materials and whose rig resolves expressions (FaceSetup::rig() has an
  // expression stage); otherwise drives nothing. Errors: the VRM's material
  // count differs from the model's.
  static eng::Result<FaceMaterials> create(const FaceSetup& face);

  // True when update() moves materials.
  bool active() const { return vrm_ != nullptr; }
  // Expression weights in the rig's controlNames() order, as
  // facial::FaceDriver::expressionWeights() and FaceSetup::expressionWeights
  // give them; an inactive driver ignores them. Errors: wrong size, a
  // non-finite weight.
  eng::Result<void> update(std::span<const float> expressionWeights);
  // The records to draw with (ModelInstance::materials): one per material of
  // the model, empty when inactive.
  std::span<const eng::vk::InstanceMaterial> materials() const { return materials_; }

 private:
  std::shared_ptr<const facial::VrmExpressionSet> vrm_;
  std::vector<facial::VrmMaterialState> rest_;
  std::vector<facial::VrmMaterialState> moved_;
  std::vector<float> effective_;
  std::vector<eng::vk::InstanceMaterial> materials_;
};

}  // namespace app
