#include "editor/app/landmark_panel.h"

#include <imgui.h>

#include <cstdio>

#include "editor/app/tooltip.h"
#include "importers/load_face.h"

namespace editor {

namespace {

// A click this close to a point (pixels) picks it.
constexpr float kPickReachPixels = 8.0f;

// The re-rigged face can stand in for the shown one when its meshes carry the
// same targets in the same order (the weights' layout is unchanged).
bool sameTargets(const eng::Model& a, const eng::Model& b) {
  if (a.meshes.size() != b.meshes.size()) return false;
  for (size_t m = 0; m < a.meshes.size(); ++m)
    if (a.meshes[m].targetNames != b.meshes[m].targetNames) return false;
  return true;
}

}  // namespace

bool LandmarkPanel::failed(const std::string& why) {
  message_.report(why, true);
  return false;
}

bool LandmarkPanel::pressShow(const app::FaceSetup& face) {
  file_ = face.model().sourcePath;
  auto loaded = importers::loadFace(file_, {.dressForDisplay = true});
  if (!loaded) return failed(loaded.error().message);
  std::error_code ec;
  const std::filesystem::path beside = app::landmarksBeside(file_);
  auto landmarks = app::faceLandmarks(*loaded, std::filesystem::is_regular_file(beside, ec) ? beside : std::filesystem::path());
  if (!landmarks) return failed(landmarks.error().message);
  auto edit = LandmarkEditModel::create(loaded->model, *landmarks, file_.string());
  if (!edit) return failed(edit.error().message);
  edit_.emplace(std::move(*edit));
  const std::optional<app::StandingUp> up = app::standingUp(*landmarks);
  standUp_ = up ? up->turn : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  message_.report("68 landmarks from " + landmarks->source, false);
  return true;
}

autorig::PictureCamera LandmarkPanel::fileCamera(const autorig::PictureCamera& view) const {
  return {view.viewProjection * glm::mat4_cast(standUp_), view.imageSize};
}

bool LandmarkPanel::clickAt(glm::vec2 pixel, const autorig::PictureCamera& camera) {
  if (!edit_) return false;
  const int index = edit_->pointAt(pixel, kPickReachPixels, fileCamera(camera));
  if (index < 0) return false;
  (void)edit_->select(index);  // in range: pointAt found it
  return true;
}

bool LandmarkPanel::dragSelected(glm::vec2 pixels, const autorig::PictureCamera& camera) {
  if (!edit_) return failed("landmarks: press Show first");
  if (auto moved = edit_->moveSelected(pixels, fileCamera(camera)); !moved) return failed(moved.error().message);
  return true;
}

bool LandmarkPanel::selectAndMove(int index, glm::vec2 pixels, const autorig::PictureCamera& camera) {
  if (!edit_) return failed("landmarks: press Show first");
  if (auto selected = edit_->select(index); !selected) return failed(selected.error().message);
  if (!dragSelected(pixels, camera)) return false;
  const glm::vec3& p = edit_->points()[size_t(index)];
  char text[160];
  std::snprintf(text, sizeof text, "landmark %d moved to (%.4f, %.4f, %.4f)", index, p.x, p.y, p.z);
  message_.report(text, false);
  return true;
}

bool LandmarkPanel::pressRerun(const app::FaceSetup& face) {
  if (!edit_) return failed("landmarks: press Show first");
  if (!rigger_) {
    auto rigger = app::FaceAutorig::load();
    if (!rigger) return failed(rigger.error().message);
    rigger_.emplace(std::move(*rigger));
  }
  auto rigged = edit_->rerun([&](const eng::Model& face, const autorig::FaceLandmarks& landmarks) -> eng::Result<eng::Model> {
    auto made = rigger_->rig(face, landmarks, file_.string());
    if (!made) return made.error();
    return std::move(made->model);
  });
  if (!rigged) return failed(rigged.error().message);
  eng::turnAtRoots(*rigged, standUp_);  // shown as the view shows the face
  rigged_.emplace(std::move(*rigged));
  ++riggedRevision_;
  message_.report(sameTargets(*rigged_, face.model())
                      ? "transfer run again from the landmarks as they are"
                      : "transfer run again, but not shown: " + face.name() + " was not rigged on the fly (its targets differ)",
                  false);
  return true;
}

bool LandmarkPanel::pressSave() {
  if (!edit_) return failed("landmarks: press Show first");
  const std::filesystem::path path = app::landmarksBeside(file_);
  if (auto saved = edit_->save(path); !saved) return failed(saved.error().message);
  message_.report("landmarks saved to " + path.string(), false);
  return true;
}

const eng::Model* LandmarkPanel::shownInstead(const eng::Model& shown) const {
  return rigged_ && sameTargets(*rigged_, shown) ? &*rigged_ : nullptr;
}

void LandmarkPanel::draw(const app::FaceSetup& face) {
  if (!edit_) {
    ImGui::TextWrapped("The 68 points the face's targets were made from.");
    if (ImGui::Button("Show landmarks")) pressShow(face);
    tooltip("Draw the 68 landmarks the face was rigged from over the view, to move them");
  } else {
    ImGui::Text("selected: %s", edit_->selected() < 0 ? "none (click a point)" : std::to_string(edit_->selected()).c_str());
    ImGui::TextDisabled("drag a point to move it over the skin");
    if (ImGui::Button(edit_->dirty() ? "Re-run transfer *" : "Re-run transfer")) pressRerun(face);
    tooltip("Rig the face again from the points as they are now (* : moved since the last run)");
    ImGui::SameLine();
    if (ImGui::Button(edit_->unsaved() ? "Save *" : "Save")) pressSave();
    tooltip("Save the points as <face>.landmarks.json beside the face (* : unsaved)");
  }
  message_.draw();
}

void LandmarkPanel::drawOverlay(ImDrawList* draw, const autorig::PictureCamera& camera) const {
  if (!edit_) return;
  const ImU32 rim = IM_COL32(20, 24, 32, 220);
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const std::optional<glm::vec2> at = autorig::projectToPicture(fileCamera(camera), edit_->points()[i]);
    if (!at) continue;
    const bool selected = int(i) == edit_->selected();
    const float radius = selected ? 4.5f : 3.0f;
    draw->AddCircleFilled({at->x, at->y}, radius + 1.2f, rim, 12);
    draw->AddCircleFilled({at->x, at->y}, radius, selected ? IM_COL32(255, 180, 60, 255) : IM_COL32(120, 255, 140, 255), 12);
  }
}

}  // namespace editor
