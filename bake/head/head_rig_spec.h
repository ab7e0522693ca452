#pragma once
// The built-in head's landmarks and action units as data
// (data/head_landmarks.json): named anatomical landmarks defined relative to
// the generated head, and per action unit the landmark displacements that an
// RBF deformation turns into a morph target. See the file's "about" entry for
// the format; parse errors name the file, the JSON path and the problem.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "facial/runtime/rbf.h"

namespace bake {

struct LandmarkDef {
  enum class Kind { Surface, Feature, Position };
  std::string name;
  Kind kind = Kind::Surface;
  glm::vec2 xy{0.0f};        // Surface: front-projected point, snapped onto the skin along -Z
  std::string feature;       // Feature: a point the generator knows ("eye_L.upper_lid")
  glm::vec3 position{0.0f};  // Position: explicit (points inside the head)
  glm::vec3 offset{0.0f};    // added after resolving
};

// Mesh parts an action unit may move.
enum class HeadPart : uint8_t { Skin, Mouth, TeethUpper, TeethLower, Tongue };
inline constexpr int kHeadPartCount = 5;
std::string_view headPartName(HeadPart part);

struct MaskDef {
  enum class Jaw { Any, Upper, Lower };  // side of the lip seam (split exactly at the lips)
  enum class Side { Both, Left, Right };
  uint8_t parts = 0b00011;  // bit per HeadPart; default skin + mouth interior
  Jaw jaw = Jaw::Any;
  Side side = Side::Both;
  // Weight 1 within `radius` of a moved landmark, fading to 0 at radius + feather.
  float radius = 0.03f;
  float feather = 0.02f;
  bool includes(HeadPart p) const { return (parts >> static_cast<int>(p)) & 1u; }
};

struct DisplacementDef {
  std::string landmark;
  glm::vec3 by{0.0f};  // metres
  std::string to;      // when set: move onto this landmark's rest position, then add `by`
};

struct DeformPartDef {
  std::vector<DisplacementDef> moves;
  std::vector<std::string> pins;  // held still even outside the mask
  std::vector<std::string> free;  // never held still
  MaskDef mask;
};

struct ActionUnitDef {
  std::string name;  // canonical channel name (facial/runtime/rig/action_units.h)
  std::vector<DeformPartDef> parts;
};

struct DetailLayerDef {
  std::string layer;   // painter layer name (skinDetailLayerNames())
  std::string target;  // action unit whose weight fades it in
  float strength = 1.0f;
};

struct AnchorDef {
  std::string name;
  glm::vec3 position{0.0f};
};

struct HeadRigSpec {
  std::string source;  // file name, for messages
  facial::RbfKernel kernel;
  std::vector<LandmarkDef> landmarks;  // mirrored entries already expanded
  std::vector<AnchorDef> anchors;      // fixed in every deformation
  std::vector<ActionUnitDef> actionUnits;
  std::vector<DetailLayerDef> detailLayers;

  const LandmarkDef* findLandmark(std::string_view name) const;
};

// Parses and validates; `source` names the input in error messages.
eng::Result<HeadRigSpec> parseHeadRigSpec(std::string_view json, const std::string& source);
eng::Result<HeadRigSpec> loadHeadRigSpec(const std::filesystem::path& path);

}  // namespace bake
