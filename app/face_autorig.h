#pragma once
// Expression targets made for a face that has none (issue 33), as the
// programs run it: the built-in head (data/head.glb) loaded once with its
// posed face, landmarks and parts (the source, autorig/builtin_source.h), the face's landmarks found on
// a front view (app/face_landmark_finder.h) or read from a file, its parts
// told apart, the head's action units and the ARKit 52 carried over
// (autorig/target_transfer.h).
//
//   auto face = importers::loadFace("face.glb", {.dressForDisplay = true});
//   auto landmarks = app::faceLandmarks(*face);
//   auto rigger = app::FaceAutorig::load();
//   auto rigged = rigger->rig(face->model, *landmarks, "face.glb");  // rigged->model has the new targets
//
// Commands that pose emotions rig such faces on the fly (FaceSetup::load):
// autorigCached() keeps the result under the user's cache, keyed by the
// model's bytes (and those of the files it reads beside it: filesReadWith),
// the head's bytes, the program's build and kAutorigVersion,
// so only the first run pays for the render, the detection and the transfer
// (3.5 s for rpm-visemes.glb on the 2-core CI machine; a cached run adds
// reading both files, about 0.3 s of 2 s for `express` there).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "autorig/face_landmarks.h"
#include "autorig/target_transfer.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "importers/load_face.h"

namespace app {

// Part of the cache key (with the program's size and time, so a rebuilt
// program rigs anew): bump it when the rigged file's layout changes.
inline constexpr std::string_view kAutorigVersion = "autorig-39";  // 2: the ARKit 52; 3: lid points on the lids, each column of an eye closed; 4: welded lips cut, a mouth bag; 5: cut along the crease; 6: lower teeth drop with the lip; 7: own mouthSmile split into AU12; 8: own mouthOpen as AU26; 9: a scan's eyes in its skin; 10: own eyesClosed as AU45; 11: no gaze for a scan's eyes; 12: units from own ARKit shapes; 13: its landmarks kept beside it; 14: a scan's eyes cut free, eyeballs behind them; 15: the head's wrinkle and colour layers carried; 16: torn lips mended, seam copies labelled as one; 19: a face's own lower teeth drop with its lip; 20: made deltas kept in mesh units under a large scale down; 21: a triangle soup welded; 22: hard edges and flat shading rigged as one surface; 23: lid margins read off the rim; 24: a beard moves as the skin under it; 25: layers and lenses told by shape, see-through primitives no skin for the landmarks; 26: lips told welded from their outer borders; 27: the warp smoothed at the landmarks but the lips' corners and middles, the jaw scaled by its turn at the lower lip; 28: the inner lips' middles smoothed, the mouth corners' spacing steadied (and eye corners cast no deeper than the brows allow); 29: the lips' line a parabola; 30: a lip's rim labelled by the side its triangles lie on; 31: a carried mouth drawn from inside only; 32: mouthPress lifts the lower lip (AU24 + AU17); 33: so does mouthRollLower (AU28 + AU17); 34: painted brows rise as one piece; 35: made units keep the head's calibration; 36: jawForward slides the whole jaw; 37: mouthShrugUpper raises the upper lip whole; 38: mouthLowerDown draws the lower lip down and back; 39: cheekSquint leaves the lids

// Why a loaded face cannot show emotions, or "" when it can (or when it is not
// autorig's to decide): no rig map names its targets (a rig map, given or in
// <data>/rigmaps, is the user's word), it is a glTF or OBJ face (VRM, CANDIDE-3
// and OBJ keyframe sets have rigs of their own; a VRM whose expressions for the
// emotions bind nothing is rigged as a glTF face), and either no scheme recognises
// its targets (`rig` failed as Unsupported) or the rig it has cannot emote
// (facial::showsEmotions: visemes only, blink only, mouth shapes without
// brows). E.g. "its 15 targets are
// visemes (lip sync) only", "it has no morph targets".
std::string autorigReason(const importers::LoadedFace& face, const eng::Result<facial::RigCalibration>& rig,
                          const std::filesystem::path& rigmapFile);

// Whether a face autorigReason() picked shows some emotions on its own: its
// rig moves the brows or the lip corners, not both. Autorig fills in what it
// lacks; when autorig cannot (no face found) or --no-autorig says not to,
// the face is used as it is, with a warning, not refused.
bool emotesInPart(const eng::Result<facial::RigCalibration>& rig);

// Whether a face autorigReason() picked keeps its own rig when autorig is not
// wanted (--no-autorig) or cannot run, with a warning, instead of being
// refused: it emotesInPart, or it is a VRM (its expressions are its author's).
bool keepsOwnRig(const importers::LoadedFace& face, const eng::Result<facial::RigCalibration>& rig);

// What to say of a face autorigReason() picked, before what autorig did or
// why it could not: the rig's own error when it has no rig (it names the file
// and suggests a rig map), else "<model>: cannot show emotions: <reason>"
// ("shows emotions only in part" for a face that emotesInPart).
std::string cannotEmoteLine(const std::filesystem::path& model, const std::string& reason,
                            const eng::Result<facial::RigCalibration>& rig);

struct AutorigResult {
  eng::Model model;                  // the face with the new targets
  autorig::FaceLandmarks landmarks;  // where its landmarks were taken from (source)
  autorig::TransferReport report;    // targets made, kept, left out
  std::vector<std::string> partNotes;  // how its parts were told apart (autorig::FaceParts::notes)
};

// A face's landmarks: read from `landmarksFile` when given and checked to lie
// on the face (errors name the file),
// else found on a front view of its display model (errors name the file: "no
// face found in a front view of cube.glb ..."). Called before
// FaceAutorig::load, so a face without one fails before the head is prepared.
eng::Result<autorig::FaceLandmarks> faceLandmarks(const importers::LoadedFace& face,
                                                  const std::filesystem::path& landmarksFile = {});

class FaceAutorig {
 public:
  // The source head: `head` (empty: app::defaultModelPath()), its parts and
  // landmarks from its own layout (autorig::builtInSource). Errors name the file.
  static eng::Result<FaceAutorig> load(const std::filesystem::path& head = {});

  // `face` (LoadedFace::model without shapes: undressed, as saved) with the
  // head's targets carried over, through `landmarks` (faceLandmarks). Errors
  // start with `faceName`.
  eng::Result<AutorigResult> rig(const eng::Model& face, const autorig::FaceLandmarks& landmarks,
                                 const std::string& faceName, const autorig::TransferOptions& options = {}) const;

  const std::filesystem::path& headPath() const { return headPath_; }

 private:
  FaceAutorig() = default;
  std::filesystem::path headPath_;
  std::unique_ptr<eng::Model> head_;  // SourceFace points at it: a stable address
  autorig::SourceFace source_;
  // The head's action-unit strengths as the runtime calibrates them (its rig
  // map's too), which the units made from its own keep (eng::Model::calibration).
  std::vector<std::pair<std::string, float>> headScales_;
};

// Where rigged faces are kept: $XDG_CACHE_HOME/facial/autorig, else
// $HOME/.cache/facial/autorig, else <temp>/facial-autorig.
std::filesystem::path autorigCacheDirectory();

// Target names, each once however many meshes carry it (sorted).
struct TargetChanges {
  std::vector<std::string> made;  // names the rigged face has that the face had not
  std::vector<std::string> kept;  // the face's own names (all kept)
};
TargetChanges targetChanges(const eng::Model& face, const eng::Model& rigged);

struct CachedAutorig : TargetChanges {
  std::filesystem::path path;        // the rigged .glb in the cache
  bool reused = false;               // found there, not made now
  std::vector<std::string> warnings; // parts left out (when made now)
  // Where its landmarks lie (beside `path`, <stem>.landmarks.json): how the
  // file holds the face.
  autorig::FaceLandmarks landmarks;
};

// How to stand up a face its file holds lying, looking away or turned (a
// Z-up export, a scan as captured), from its landmarks; nullopt when it
// stands as glTF's axes say (its front within kQuarterTurnSlackDegrees of
// +Z, its top of +Y). Within that slack of another quarter-turn pose, the
// quarter turn (a Z-up export stands exactly as it was made); further off,
// the face turned to look along +Z, level (kLevelPitchDegrees), its eyes
// across X, unless its points were only fitted in its targets' box. With how it lies, for notes ("looks along -Y, its top along +Z").
inline constexpr float kQuarterTurnSlackDegrees = 15.0f;
struct StandingUp {
  glm::quat turn;
  std::string howItLies;
};
std::optional<StandingUp> standingUp(const autorig::FaceLandmarks& landmarks);

// The files a face file (`bytes`: its content) reads beside it, which key
// its rig in the cache with its own bytes: a .gltf's or GLB's buffers and
// images outside it (not data: URIs), an OBJ's material libraries and their
// texture maps. Missing ones are listed too.
std::vector<std::filesystem::path> filesReadWith(const std::filesystem::path& model, std::string_view bytes);

// Where a face's own landmarks file is looked for when it is rigged on the
// fly: beside it, <stem>.landmarks.json (for faces the detector misses).
std::filesystem::path landmarksBeside(const std::filesystem::path& modelPath);

// The rigged face of the glTF file `modelPath`: from the cache when it is
// there, else made (FaceAutorig, through landmarksBeside() when that file
// exists) and written there whole (.partial, renamed).
eng::Result<CachedAutorig> autorigCached(const std::filesystem::path& modelPath);

// `face` (loaded from the glTF file `modelPath` with `options`) replaced by
// its rigged copy (autorigCached) loaded with the same options, stood up
// when its file holds it lying or looking away (standingUp: the commands
// that draw it show the face, not the top of its head); its model
// keeps the user's file as sourcePath, so messages never name the cache.
eng::Result<CachedAutorig> loadAutorigged(const std::filesystem::path& modelPath,
                                          const importers::LoadFaceOptions& options, importers::LoadedFace& face);

// Writes `model` to `path` whole: a .partial file beside it, renamed into place.
eng::Result<void> saveModelAtomically(const eng::Model& model, const std::filesystem::path& path);

}  // namespace app
