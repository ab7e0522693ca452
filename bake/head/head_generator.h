#pragma once
// The project's built-in head, generated entirely by code: skin with eyelids,
// lip seam and mouth pocket; eyeballs, teeth, tongue, ears; painted textures
// with expression detail layers; and one morph target per FACS action unit
// (canonical names from facial/runtime/rig/action_units.h), baked by RBF
// deformation of the landmarks in data/head_landmarks.json.
//
// Model layout: mesh "Head" (primitives skin, mouth interior, upper teeth,
// lower teeth, tongue; all carry every action-unit target), meshes "EyeLeft" and
// "EyeRight" (no targets; each on a node at its eyeball's centre, the eye's
// joint) and mesh "Ears" (no targets), each on its own node under root node
// "BuiltInHead".
// Deterministic: the same spec gives the same model, bit for bit.
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "bake/head/au_baker.h"
#include "bake/head/head_rig_spec.h"

namespace bake {

struct HeadOptions {
  int skinTextureSize = 1024;
  int detailTextureSize = 512;
  int eyeTextureWidth = 512;  // height is half of it
};

// Primitive order inside mesh "Head".
enum class HeadPrimitive : int { Skin = 0, Mouth = 1, TeethUpper = 2, TeethLower = 3, Tongue = 4 };

struct GeneratedHead {
  eng::Model model;
  LandmarkPoints landmarks;  // rest positions, as resolved on the generated skin
};

eng::Result<GeneratedHead> generateHead(const HeadRigSpec& spec, const HeadOptions& options = {});

}  // namespace bake
