#pragma once
// How a face that arrives without textures is shown. A scan or sculpt
// exported untextured (facecap, many ARKit captures) is one plain white
// material on skin, eyeballs and teeth alike: a plaster cast whose blank
// eyes and washed-out shading hide every expression. For display, such a
// face is dressed:
//  - eyeballs get the procedural eye (procedural_eyes.h);
//  - teeth and tongue, found by name, get ivory and a muted pink;
//  - the skin -- the untextured, white material of a mesh that carries morph
//    targets, on a model that is a face (it has eyeballs, or a mesh or node
//    named head or face) -- gets a neutral mid skin tone, so shading keeps its contrast
//    where a pale face would clip;
//  - all of these get ambient occlusion baked into their vertex colours
//    (vertex_occlusion.h), so the mouth's inside, nostrils and the rim of
//    the lids read as deep.
// Anything textured or given a colour by its author is left as it is.
//
// Dressing is a step of loading that the caller asks for, never done behind
// its back: the renderer draws a model as given. The programs ask for it
// (importers::loadFace with LoadFaceOptions::dressForDisplay) and draw the
// dressed copy, keeping the model as loaded for what they inspect, rig and
// export; an embedder that wants the same look calls dressedForDisplay.
#include <cstddef>
#include <optional>
#include <vector>

#include "engine/scene/model.h"

namespace importers {

struct FaceDressing {
  size_t eyes = 0;   // primitives dressed as eyeballs
  size_t mouth = 0;  // teeth and tongue primitives
  size_t skin = 0;   // primitives given the skin tone
  size_t total() const { return eyes + mouth + skin; }
};

// What dressUntexturedFace would change, without changing anything.
FaceDressing planFaceDressing(const eng::Model& model);
// Dresses `model` in place; what was dressed (all 0: nothing changed).
FaceDressing dressUntexturedFace(eng::Model& model);
// A dressed copy of `model` to draw, or nullopt when nothing in it needs
// dressing (draw the model itself).
std::optional<eng::Model> dressedForDisplay(const eng::Model& model);

}  // namespace importers
