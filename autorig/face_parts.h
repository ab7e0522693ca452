#pragma once
// What each vertex of a face is: skin, an eyeball, teeth, tongue, lashes,
// brows, glasses, hair or something else (body, clothes). Found per
// connected component, by the names of the material, mesh and nodes first and
// then by geometry against the landmarks (a closed near-sphere behind an eye
// is an eyeball; a component inside the mouth below the lip line is the lower
// teeth...). The transfer moves each kind its own way: skin, lashes and brows
// follow the skin; eyeballs, upper teeth, glasses and hair stay; lower teeth
// and tongue turn with the jaw.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/face_landmarks.h"
#include "autorig/posed_face.h"
#include "engine/scene/model.h"

namespace autorig {

enum class FacePart : unsigned char {
  Skin,
  EyeballRight,  // the subject's right eye (landmarks 36-41)
  EyeballLeft,   // landmarks 42-47
  UpperTeeth,
  LowerTeeth,
  Tongue,
  Lashes,
  Brows,
  Glasses,
  Hair,
  // A layer lying on the skin, a mesh of its own (a beard, a moustache,
  // stubble, face paint, Ready Player Me's "facewear"): it moves as the skin
  // under it.
  SkinLayer,
  Other,  // body, clothes, anything away from the face: never moved
};

// "skin", "right eyeball", ... for reports.
const char* facePartName(FacePart part);

struct FaceParts {
  // One entry per PosedFace primitive (same order), one part per vertex.
  std::vector<std::vector<FacePart>> vertexParts;
  // Eyeball centres and radii in world space (index 0: right eye, 1: left),
  // from the eyeball meshes when there are any, else estimated from the eye
  // landmarks (behind the lid line by the eye's typical depth).
  std::array<glm::vec3, 2> eyeCentres{};
  std::array<float, 2> eyeRadii{};
  bool eyeballsFound = false;
  // An eye that is the skin (a scan's: the eye painted on a ball inside the
  // lids): it stays still, and no gaze turns it, since turning painted skin
  // drags the lids' texels into the opening.
  std::array<bool, 2> eyesInTheSkin{};
  // One line per decision a user may want to check ("Wolf3D_Teeth: upper
  // and lower teeth, split at y = 1.62"), for `facial rig` and notes.
  std::vector<std::string> notes;
};

// The part the names of a primitive's material, mesh, node and the node's
// parents say it is, or nullopt when they say nothing (geometry decides).
// Any eyeball comes back as EyeballRight: its side is the landmarks' call.
std::optional<FacePart> facePartFromNames(const eng::Model& model, const PosedPrimitive& primitive);

FaceParts findFaceParts(const eng::Model& model, const PosedFace& posed, const FaceLandmarks& landmarks);

// The eyeball a face without one would have: centred behind the middle of
// the lid margins (landmarks 36-41, 42-47), its radius 0.45 of the eye's
// width (a 24 mm ball behind a 28 mm opening). `eye` 0: right, 1: left.
struct Eyeball {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  glm::vec3 margins{0.0f};  // the middle of the lid margins it sits behind
};
Eyeball eyeballBehindTheLids(const FaceLandmarks& landmarks, size_t eye);

}  // namespace autorig
