#pragma once
// Sculpting an expression with RBF control points: points on the face (rest
// positions, world space), a displacement per point, a kernel, and optional
// pins at the corners of the model's box (zero displacement) so a lone moved
// point bends the face around it instead of shifting all of it. The RBF
// solve is factored once per layout (points, kernel, pins); displacement
// edits only re-apply the baked deformer. Plain C++ (no UI, no Vulkan).
//
//   SculptModel sculpt(surface.restPositions(), bounds);
//   auto i = sculpt.addPoint("mouth_corner_L", hit.restPoint);
//   sculpt.setDisplacement(*i, {0, 0.004f, 0});
//   sculpt.prepare();                                // refactors only if the layout changed
//   sculpt.vertexDisplacements(out);                 // world space, one per surface vertex
//   bakeSculptTarget(model, surface, sculpt, "smirk");  // then eng::saveModel(model, "face.glb")
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "editor/model_surface.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/rbf.h"

namespace editor {

struct SculptPoint {
  std::string name;
  glm::vec3 rest{0.0f};          // world space, on the rest surface
  glm::vec3 displacement{0.0f};  // world space
};

class SculptModel {
 public:
  // vertices: the surface's rest positions (world space), kept by reference
  // and must outlive the model. bounds: the model's box, for the pins.
  SculptModel(std::span<const glm::vec3> vertices, const eng::Aabb& bounds);

  std::span<const SculptPoint> points() const { return points_; }
  // Fails on a non-finite position or one closer than minSeparation() to an existing point (naming it).
  eng::Result<size_t> addPoint(std::string name, const glm::vec3& rest);
  eng::Result<void> removePoint(size_t index);
  eng::Result<void> setDisplacement(size_t index, const glm::vec3& displacement);
  void clearDisplacements();
  void clearPoints();

  const facial::RbfKernel& kernel() const { return kernel_; }
  // Fails (kernel unchanged) for k < 1 or a multiquadric c that is not > 0.
  eng::Result<void> setKernel(const facial::RbfKernel& kernel);
  bool pinsEnabled() const { return pinsEnabled_; }
  void setPinsEnabled(bool enabled);
  // The eight pins (corners of the box grown by half its size around its centre).
  std::span<const glm::vec3> pins() const { return pins_; }
  float minSeparation() const { return minSeparation_; }

  // Falloff radius (world units): vertices farther than this from every
  // control point do not move, and the edit fades out smoothly from half the
  // radius to the radius, so a sculpt stays local. 0 = no falloff (the RBF
  // field reaches the whole face). Fails (unchanged) when negative or not finite.
  float falloffRadius() const { return falloffRadius_; }
  eng::Result<void> setFalloffRadius(float radius);

  // Changes when points are added or removed, or the kernel or pins change;
  // not on displacement edits.
  uint64_t layoutRevision() const { return layoutRevision_; }
  // Factors the RBF system and bakes the vertex deformer when the layout
  // changed since the last call. Fails when there are no points, or too few
  // (RBF needs 4 non-coplanar points, pins included), or they are degenerate.
  eng::Result<void> prepare();
  bool prepared() const { return deformer_.has_value() && deformerRevision_ == layoutRevision_; }
  // Influence of point `control` (index into points()) on vertex `vertex`; prepared() required.
  // The falloff is folded in, so the preview basis matches the baked target.
  float influence(size_t vertex, size_t control) const {
    return deformer_->influence(vertex, control) * (falloff_.empty() ? 1.0f : falloff_[vertex]);
  }

  // World-space displacement of every surface vertex; out.size() == vertex count.
  // Fails when not prepared() or on a size mismatch.
  eng::Result<void> vertexDisplacements(std::span<glm::vec3> out);
  // True when some point has a non-zero displacement.
  bool hasDisplacement() const;

 private:
  std::span<const glm::vec3> vertices_;
  std::vector<SculptPoint> points_;
  std::vector<glm::vec3> pins_;
  facial::RbfKernel kernel_;
  bool pinsEnabled_ = true;
  float minSeparation_ = 1e-6f;
  float falloffRadius_ = 0.0f;
  std::vector<float> falloff_;  // per vertex when falloffRadius_ > 0, built by prepare()
  uint64_t layoutRevision_ = 1;
  uint64_t deformerRevision_ = 0;
  std::optional<facial::RbfDeformer> deformer_;
  std::vector<glm::vec3> solverDisplacements_;  // points then pins (zero)
};

// Bakes the sculpt's current displacements as a new morph target `name` on
// every primitive the surface covers (other primitives get an all-zero
// target), with position and normal deltas in each primitive's local space;
// mesh default weights and weight animations grow by one zero. Fails (model
// unchanged) for an empty or already used name, an unprepared sculpt, no
// displacement at all, or a surface not made from `model`.
eng::Result<void> bakeSculptTarget(eng::Model& model, const ModelSurface& surface, SculptModel& sculpt, std::string_view name);

// Bakes again a target that bakeSculptTarget made on a copy of this model
// (saved and reloaded, as a project does): the target `name` of every mesh of
// `from` that has it is appended to the same mesh of `to`, as bakeSculptTarget
// would. Fails (`to` unchanged) when no mesh has it, `to` already has it, or
// the meshes differ in primitives or vertex counts (another model).
eng::Result<void> copyBakedTarget(const eng::Model& from, std::string_view name, eng::Model& to);

// Live preview without re-uploading per drag: a copy of `model` with three
// targets per control point (its influence times the local x, y, z axis) on
// every surface primitive. Their weights are the points' displacement
// components, so moving a point only changes weights; the copy is rebuilt
// when the layout changes.
class SculptPreview {
 public:
  static eng::Result<SculptPreview> build(const eng::Model& model, const ModelSurface& surface, const SculptModel& sculpt);
  const eng::Model& model() const { return model_; }
  uint64_t layoutRevision() const { return layoutRevision_; }
  // out = the face's weights (the original layout) plus the displacement
  // weights, in the preview model's layout. Sizes checked.
  eng::Result<void> weights(std::span<const float> faceWeights, std::span<const SculptPoint> points, std::span<float> out) const;
  uint32_t weightCount() const { return previewTotal_; }

 private:
  eng::Model model_;
  uint64_t layoutRevision_ = 0;
  size_t pointCount_ = 0;
  std::vector<uint32_t> faceOffsets_;     // per mesh, in the original layout (+ total)
  std::vector<uint32_t> previewOffsets_;  // per mesh, in the preview layout
  std::vector<uint32_t> basisOffset_;     // per mesh: first basis target (UINT32_MAX: none)
  uint32_t previewTotal_ = 0;
};

}  // namespace editor
