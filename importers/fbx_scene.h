#pragma once
// An FBX file (binary or ASCII 7.x: Maya, 3ds Max, Blender, Mixamo, Character
// Creator, DAZ exports) as an eng::Model, the way the glTF loader makes one:
//  - every Model becomes a node (its FBX transform with pivots, offsets, pre-
//    and post-rotation and rotation order, as one matrix), under a root that
//    turns the file's axes (GlobalSettings) to glTF's Y up, +Z front, and its
//    units to metres;
//  - each mesh Model's Geometry becomes a mesh, one primitive per material,
//    polygons fanned into triangles, its geometric transform baked in; the
//    first layer's normals, texture coordinates and colours are read;
//  - blend shape channels become morph targets, named after their channel
//    (a face's ARKit or FACS names come through), DeformPercent the default
//    weight;
//  - skin clusters become a skin over the bone Models, bind matrices from
//    the clusters (TransformLink), four or more influences per vertex;
//  - materials take their diffuse colour and diffuse texture: embedded
//    (Video Content) or a file beside the FBX (confined to its folder, also
//    looked for in its `<name>.fbm` folder as the FBX SDK extracts them).
//  - each AnimationStack's first layer becomes an animation: blend shape
//    DeformPercent curves as weights, Lcl T/R/S curves as node channels.
// Not read, with a warning: in-between shapes (the full shape is kept),
// animation layers after the first. Only the first geometry layer is read. Malformed geometry is skipped with a
// warning naming it; a file with nothing drawable is an error.
#include <cstdint>
#include <filesystem>
#include <span>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace importers {

// `path` names the file in messages and places textures named by file.
eng::Result<eng::Model> importFbx(std::span<const uint8_t> bytes, const std::filesystem::path& path);

}  // namespace importers
