#pragma once
// RBF sculpt panel: control points picked on the face (a click ray-cast
// against the CPU-morphed mesh, or a named landmark of the built-in head),
// a displacement per point (XYZ drags, or Shift+drag in the view in the
// screen plane), the kernel, a live whole-mesh preview, "bake" as a named
// morph target and "save" as .glb. The sculpt itself is editor/sculpt_model.h;
// this panel owns the working copy of the model the bakes go into and tells
// the app which model to show (it never touches the renderer).
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_setup.h"
#include "editor/app/face_delegate.h"
#include "editor/model_surface.h"
#include "editor/sculpt_model.h"
#include "engine/scene/weights.h"

namespace editor {

class SculptPanel {
 public:
  // landmarksFile: the built-in head's data/head_landmarks.json, or empty for other models.
  eng::Result<void> create(const app::FaceSetup& face, const std::string& landmarksFile);
  void draw();

  // Viewport hooks (the app turns mouse input into world rays and deltas).
  // Each returns false after reporting why in the panel (and the log).
  bool pickMode() const { return pickMode_; }
  void setPickMode(bool on) { pickMode_ = on; }
  // Adds a point where the ray meets the face as shown (faceWeights: the face layout) and selects it.
  bool pick(const glm::vec3& origin, const glm::vec3& direction, std::span<const float> faceWeights);
  bool hasSelection() const { return selected_ >= 0; }
  // Moves the selected point by a world-space delta (Shift+drag, the XYZ drags).
  bool dragSelected(const glm::vec3& worldDelta);

  // What the widgets do (the --script runs these too); false after reporting why.
  bool pressAddLandmark(const std::string& name);
  bool hasLandmark(const std::string& name) const;
  // The kernel combo (and c for the multiquadric; c <= 0 keeps the current c).
  bool chooseKernel(facial::RbfKernelType type, float c);
  // The falloff slider (world units, 0 = the whole face follows).
  bool chooseFalloff(float radius);
  bool pressBake(const std::string& name);
  bool pressSave(const std::string& path);

  // What to draw: changes revision when the model to upload changes.
  uint64_t displayRevision() const { return displayRevision_; }
  const eng::Model& displayModel() const;
  // faceWeights (the FaceSetup layout) -> weights of displayModel().
  void displayWeights(std::span<const float> faceWeights, std::vector<float>& out);
  // Keeps the preview in step with the sculpt (call once a frame before drawing).
  void refresh();

  std::span<const SculptPoint> points() const { return sculpt_->points(); }
  // Where the points are on the face as shown (faceWeights: the face layout):
  // `onFace` follows the face's targets (expressions, baked sculpts) from the
  // triangle each point was picked on, `moved` adds the point's displacement.
  void pointsOnFace(std::span<const float> faceWeights, std::vector<glm::vec3>& onFace, std::vector<glm::vec3>& moved);
  int selected() const { return selected_; }
  float modelSize() const { return size_; }
  // For tests and scripted runs.
  eng::Result<size_t> addLandmark(const std::string& name);
  eng::Result<void> bake(const std::string& name);
  eng::Result<void> saveModel(const std::string& path);
  SculptModel& sculpt() { return *sculpt_; }

  // Projects (editor/project.h): the baked targets with their slider weights,
  // in bake order; restore() goes back to the face as loaded (no points,
  // nothing baked) and bakes again the named targets of `sculpted` (a model
  // saveModel wrote for this face; null when there are none). On failure
  // nothing changes.
  std::span<const std::pair<std::string, float>> bakedTargets() const { return baked_; }
  // The face's model with the baked targets (what Save .glb writes).
  const eng::Model& workingModel() const { return working_; }
  // faceWeights (the FaceSetup layout) -> weights of workingModel(), the baked targets at their slider weights.
  void bakedWeights(std::span<const float> faceWeights, std::vector<float>& out) const {
    out.resize(workingLayout_->total());
    workingWeights(faceWeights, out);
  }
  eng::Result<void> restore(const eng::Model* sculpted, std::span<const std::pair<std::string, float>> targets);

 private:
  void workingWeights(std::span<const float> faceWeights, std::span<float> out) const;
  void drawKernel();
  void drawBakeAndSave();
  void reportPoint(size_t index);
  // Adds a point (and where it sits on the surface, for pointsOnFace) and selects it.
  eng::Result<size_t> addPoint(const std::string& name, const glm::vec3& rest, const std::optional<SurfaceHit>& hit);
  void removePoint(size_t index);
  void clearPoints();
  void rebuildWorkingLayout();

  const app::FaceSetup* face_ = nullptr;
  eng::Model working_;  // the face's model plus the targets baked so far
  std::optional<eng::WeightLayout> workingLayout_;
  std::optional<ModelSurface> surface_;
  std::optional<SculptModel> sculpt_;
  std::optional<SculptPreview> preview_;
  bool previewEnabled_ = true;
  bool pickMode_ = false;
  int selected_ = -1;
  float size_ = 1.0f;
  uint64_t displayRevision_ = 1;
  bool showingPreview_ = false;
  std::vector<float> workingScratch_;
  std::vector<std::pair<std::string, float>> baked_;  // baked targets and their preview weight
  struct Landmark {
    std::string name;
    glm::vec3 rayOrigin;  // cast along -Z onto the skin, or the point itself (rayLength 0)
    bool onSurface;
  };
  std::vector<Landmark> landmarks_;
  // Per point: the triangle corners (indices into the surface's flat vertex
  // arrays) and barycentric weights it was picked at; none for points off the surface.
  struct SurfaceAnchor {
    size_t primitive = 0;  // into surface_->primitives()
    uint32_t corner[3] = {0, 0, 0};
    glm::vec3 barycentric{0.0f};
  };
  std::vector<std::optional<SurfaceAnchor>> anchors_;
  int landmarkChoice_ = 0;
  int kernelChoice_ = 0;
  float multiquadricC_ = 0.1f;
  float solveMs_ = 0.0f;
  char bakeName_[64] = "sculpted";
  char savePath_[512] = "sculpted.glb";
  PanelMessage message_;
};

}  // namespace editor
