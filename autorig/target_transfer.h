#pragma once
// The built-in head's action units carried onto another face (the study's RBF
// deformation): the head warped onto the face through the landmarks (RBF with
// the affine term), a dense correspondence grown from them by closest points
// on the warped surface (upper lip to upper lip, upper lid to upper lid), and
// each target's displacements taken over, scaled by the warp's local
// Jacobian. Then what makes a face look right: lids slide over the eyeball,
// the jaw turns about its hinge with the lower teeth and tongue, eyeballs,
// upper teeth, glasses and hair stay, normals are recomputed. The ARKit 52
// shapes are built from the transferred units (autorig/arkit_from_units.h).
#include <string>
#include <vector>

#include "autorig/face_landmarks.h"
#include "autorig/face_parts.h"
#include "autorig/posed_face.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace autorig {

// The face the targets come from (the built-in head, data/head.glb), with its
// landmarks and parts: autorig::builtInSource (autorig/builtin_source.h) sets
// it up, its landmarks where dlib puts them on the head.
struct SourceFace {
  const eng::Model* model = nullptr;
  PosedFace posed;
  FaceLandmarks landmarks;
  FaceParts parts;
};

struct TransferOptions {
  bool actionUnits = true;  // the head's AU targets (AU1_InnerBrowRaiser, ...)
  bool arkit = true;        // the ARKit 52 built from them (jawOpen, mouthSmileLeft, ...)
  // Bounded memory: every made target holds a displacement per skin vertex
  // (63 targets of a 600k-vertex face are about 1.4 GB with their normals).
  // A face over this is refused with its count.
  size_t maxSkinVertices = 600000;
  // The head's wrinkle and colour layers carried onto the skin's texture
  // (autorig/detail_transfer.h, with the action units); off, the face's
  // textures are left as they are: a file for an engine that does not read
  // detail layers, or a test of the shapes alone.
  bool detailLayers = true;
};

struct TransferReport {
  std::vector<std::string> made;      // target names added to the face
  std::vector<std::string> kept;      // names the face already had (not replaced)
  std::vector<std::string> warnings;  // parts left out and why
  std::vector<std::string> notes;     // units made from the face's own shapes
  std::vector<std::string> own;       // those units' names (AU12_LipCornerPuller_L from mouthSmile, ...)
  std::vector<std::string> details;   // the head's wrinkle and colour layers carried (autorig/detail_transfer.h)
};

struct TransferResult {
  eng::Model model;  // the face with the new targets on its skin meshes (and teeth, tongue)
  TransferReport report;
};

// Errors (naming sizes): no skin vertex near the landmarks, landmarks that do
// not make a face (collapsed, mirrored, off the surface), a source without
// action units.
eng::Result<TransferResult> transferTargets(const SourceFace& source, const eng::Model& face, const PosedFace& posed,
                                            const FaceLandmarks& landmarks, const FaceParts& parts,
                                            const TransferOptions& options = {});

}  // namespace autorig
