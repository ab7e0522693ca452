#pragma once
// How a face that arrives without textures is shown. A scan or sculpt
// exported untextured (facecap, many ARKit captures) is one plain white
// material on skin, eyeballs and teeth alike: a plaster cast whose blank
// eyes and washed-out shading hide every expression. For display only (the
// loaded model itself is not changed), such a face is dressed:
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
#include <cstddef>
#include <vector>

#include "engine/scene/model.h"

namespace eng {

struct FaceDressing {
  size_t eyes = 0;   // primitives dressed as eyeballs
  size_t mouth = 0;  // teeth and tongue primitives
  size_t skin = 0;   // primitives given the skin tone
  size_t total() const { return eyes + mouth + skin; }
};

// Parts of a face that sit inside the head: eyeballs, teeth, tongue and the
// mouth's inside, found by the names of the primitive's material, mesh or
// nodes, and only where the primitive's rest bounds lie within another
// primitive's (the head around it). The shadows they cast fall into the eye
// sockets and the mouth, which the head's own shadow and its occlusion
// already darken: a renderer may leave them out of its shadow map.
// One flag per primitive, mesh-major.
std::vector<std::vector<bool>> partsInsideTheHead(const Model& model);

// What dressUntexturedFace would change, without changing anything.
FaceDressing planFaceDressing(const Model& model);
FaceDressing dressUntexturedFace(Model& model);

}  // namespace eng
