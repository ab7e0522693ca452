#pragma once
// The parts of a face that sit inside the head (eyeballs, teeth, tongue, the
// mouth's inside), known by their names. The renderer needs them to leave
// them out of its shadow map; the face dressing (importers/face_dressing.h)
// names the same parts to colour them.
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/model.h"

namespace eng {

// Parts of a face that sit inside the head: eyeballs, teeth, tongue and the
// mouth's inside, found by the names of the primitive's material, mesh or
// nodes, and only where the primitive's rest bounds lie within another
// primitive's (the head around it). The shadows they cast fall into the eye
// sockets and the mouth, which the head's own shadow and its occlusion
// already darken: a renderer may leave them out of its shadow map.
// One flag per primitive, mesh-major.
std::vector<std::vector<bool>> partsInsideTheHead(const Model& model);

// Whether `name` names an eyeball (not a brow, lash, lid, socket...).
bool namesAnEyeball(const std::string& name);
// An eyeball that is a primitive of the face's mesh is known by its material's name.
bool materialNamesAnEyeball(const Model& model, int material);
// The mesh's name and the names of the node drawing it and up to three of its parents.
std::vector<std::string_view> meshAndNodeNames(const Model& model, size_t mesh, int node);
// Whether one of `names` contains `needle` (lower case), ignoring case.
bool anyNameContains(const std::vector<std::string_view>& names, std::string_view needle);

}  // namespace eng
