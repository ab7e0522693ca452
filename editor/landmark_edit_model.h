#pragma once
// The 68 landmarks a face was rigged from, edited in the editor (issue 33):
// shown over the face, one selected and moved over the skin (dragged in the
// picture and cast back onto the face's outer surface, so a point never
// leaves it), the transfer run again with them, and saved as a landmarks file
// (<stem>.landmarks.json beside the face is where rigging on the fly looks:
// app::landmarksBeside). Plain C++: the rigging itself is the caller's (a
// Rigger; the editor passes app::FaceAutorig's).
//
//   auto edit = LandmarkEditModel::create(face, landmarks);  // face: as loaded, without made targets
//   edit->select(48);
//   edit->moveSelected({6, -2}, camera);                     // pixels in camera's picture
//   auto rigged = edit->rerun(rigger);                       // the face with its targets made anew
//   edit->save("face.landmarks.json");
#include <filesystem>
#include <functional>
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"
#include "autorig/posed_face.h"
#include "autorig/surface_cast.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace editor {

class LandmarkEditModel {
 public:
  // The face (without the made targets) and its landmarks -> the face with targets made.
  using Rigger = std::function<eng::Result<eng::Model>(const eng::Model& face, const autorig::FaceLandmarks& landmarks)>;

  // `face` is copied. Fails when the landmarks are not on its surface
  // (autorig::checkLandmarksOnSurface, naming `name`).
  static eng::Result<LandmarkEditModel> create(const eng::Model& face, const autorig::FaceLandmarks& landmarks,
                                               const std::string& name);

  const autorig::FaceLandmarks& landmarks() const { return landmarks_; }
  std::span<const glm::vec3> points() const { return landmarks_.points; }
  const eng::Model& face() const { return *face_; }

  int selected() const { return selected_; }
  // -1 selects none. Fails (selection unchanged) outside [-1, 67].
  eng::Result<void> select(int index);
  // The landmark nearest `pixel` in `camera`'s picture within `reachPixels`, or -1.
  int pointAt(glm::vec2 pixel, float reachPixels, const autorig::PictureCamera& camera) const;
  // The selected point moved by `pixels` in `camera`'s picture, then cast
  // back onto the face's outer skin. Fails (nothing moves) when none is
  // selected, the point is behind the camera or no skin is under the new pixel.
  eng::Result<void> moveSelected(glm::vec2 pixels, const autorig::PictureCamera& camera);

  // Moved since the transfer last ran (rerun) / since the last save.
  bool dirty() const { return dirty_; }
  bool unsaved() const { return unsaved_; }
  // The face rigged again from the points as they are; clears dirty().
  eng::Result<eng::Model> rerun(const Rigger& rig);
  // The points as a landmarks file (written whole); clears unsaved().
  eng::Result<void> save(const std::filesystem::path& path);

 private:
  LandmarkEditModel() = default;
  std::unique_ptr<eng::Model> face_;  // PosedFace and the caster's triangles point into it: a stable address
  autorig::PosedFace posed_;
  std::vector<bool> outerSkin_;
  autorig::FaceLandmarks landmarks_;
  int selected_ = -1;
  bool dirty_ = false;
  bool unsaved_ = false;
};

}  // namespace editor
