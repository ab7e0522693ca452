#pragma once
// The landmarks a face was rigged from (issue 33), over the face: "Show"
// finds them as rigging on the fly does (<stem>.landmarks.json beside the
// face, else dlib on a front view: app::faceLandmarks), a click picks the
// nearest, a drag moves it over the skin, "Re-run transfer" rigs the face
// again from them (app::FaceAutorig) and "Save" writes them beside the face,
// where the next run of any command finds them. The editing itself is
// editor/landmark_edit_model.h; the app draws the re-rigged face this panel
// hands it (it never touches the renderer).
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "app/face_autorig.h"
#include "app/face_setup.h"
#include "autorig/surface_cast.h"
#include "editor/app/face_delegate.h"
#include "editor/landmark_edit_model.h"

struct ImDrawList;

namespace editor {

class LandmarkPanel {
 public:
  void draw(const app::FaceSetup& face);
  // The points over the face, projected with the view camera (its picture: the window).
  void drawOverlay(ImDrawList* draw, const autorig::PictureCamera& camera) const;

  // What the widgets and the view do (the --script runs these too); false after reporting why.
  bool pressShow(const app::FaceSetup& face);
  bool shown() const { return edit_.has_value(); }
  // A click in the view: selects the landmark within a few pixels of it; false (nothing reported) when none is.
  bool clickAt(glm::vec2 pixel, const autorig::PictureCamera& camera);
  bool dragSelected(glm::vec2 pixels, const autorig::PictureCamera& camera);
  bool selectAndMove(int index, glm::vec2 pixels, const autorig::PictureCamera& camera);
  bool pressRerun(const app::FaceSetup& face);
  bool pressSave();

  // The face rigged again from the moved points, once re-run, when it can
  // stand in for `shown` (the same targets: the weights fit); else null.
  const eng::Model* shownInstead(const eng::Model& shown) const;
  // Changes with each re-run.
  uint64_t riggedRevision() const { return riggedRevision_; }

 private:
  bool failed(const std::string& why);  // reported in the panel and the log
  // The view's camera for the points, which are the file's: a face its file
  // holds lying is shown stood up (app::loadAutorigged), turned by standUp_.
  autorig::PictureCamera fileCamera(const autorig::PictureCamera& view) const;

  std::optional<LandmarkEditModel> edit_;
  std::filesystem::path file_;  // the face's own file
  glm::quat standUp_{1.0f, 0.0f, 0.0f, 0.0f};
  std::optional<app::FaceAutorig> rigger_;
  std::optional<eng::Model> rigged_;
  uint64_t riggedRevision_ = 0;
  PanelMessage message_;
};

}  // namespace editor
