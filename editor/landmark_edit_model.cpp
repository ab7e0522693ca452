#include "editor/landmark_edit_model.h"

#include <limits>
#include <string>

namespace editor {

namespace {

// How far from the dragged-to pixel the skin may be taken (its nearest
// vertex) when the ray falls through an opening: an eye, parted lips.
constexpr float kCastReachPixels = 4.0f;

}  // namespace

eng::Result<LandmarkEditModel> LandmarkEditModel::create(const eng::Model& face, const autorig::FaceLandmarks& landmarks,
                                                         const std::string& name) {
  LandmarkEditModel model;
  model.face_ = std::make_unique<eng::Model>(face);
  model.posed_ = autorig::poseAtRest(*model.face_);
  ENG_TRY(autorig::checkLandmarksOnSurface(landmarks, *model.face_, model.posed_, name));
  model.outerSkin_ = autorig::outerSkinPrimitives(*model.face_, model.posed_);
  model.landmarks_ = landmarks;
  return model;
}

eng::Result<void> LandmarkEditModel::select(int index) {
  if (index < -1 || index >= int(autorig::kLandmarkCount))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "landmark " + std::to_string(index) + " is not one of the 68 (0-67)");
  selected_ = index;
  return {};
}

int LandmarkEditModel::pointAt(glm::vec2 pixel, float reachPixels, const autorig::PictureCamera& camera) const {
  int best = -1;
  float bestDistance = reachPixels;
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const std::optional<glm::vec2> at = autorig::projectToPicture(camera, landmarks_.points[i]);
    if (!at) continue;
    const float d = glm::distance(*at, pixel);
    if (d <= bestDistance) bestDistance = d, best = int(i);
  }
  return best;
}

eng::Result<void> LandmarkEditModel::moveSelected(glm::vec2 pixels, const autorig::PictureCamera& camera) {
  if (selected_ < 0) return eng::makeError(eng::ErrorKind::InvalidArgument, "no landmark selected to move");
  const std::string which = "landmark " + std::to_string(selected_);
  const std::optional<glm::vec2> at = autorig::projectToPicture(camera, landmarks_.points[size_t(selected_)]);
  if (!at) return eng::makeError(eng::ErrorKind::InvalidArgument, which + " is behind the camera");
  const glm::vec2 to = *at + pixels;
  const autorig::SurfaceCaster caster(*face_, posed_, outerSkin_, camera);
  const std::optional<autorig::SurfacePoint> hit = caster.cast(to, kCastReachPixels);
  if (!hit)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          which + " cannot move to pixel (" + std::to_string(int(to.x)) + ", " + std::to_string(int(to.y)) +
                              "): no skin of the face there");
  landmarks_.points[size_t(selected_)] = hit->position;
  landmarks_.source = "moved in the editor";
  dirty_ = unsaved_ = true;
  return {};
}

eng::Result<eng::Model> LandmarkEditModel::rerun(const Rigger& rig) {
  eng::Result<eng::Model> rigged = rig(*face_, landmarks_);
  if (rigged) dirty_ = false;
  return rigged;
}

eng::Result<void> LandmarkEditModel::save(const std::filesystem::path& path) {
  ENG_TRY(autorig::writeLandmarksFile(landmarks_, path));
  unsaved_ = false;
  return {};
}

}  // namespace editor
