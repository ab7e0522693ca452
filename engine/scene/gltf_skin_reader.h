#pragma once
// The skinning half of glTF import (used by gltf_loader.cpp): a primitive's
// JOINTS_n / WEIGHTS_n, the skins with their inverse bind matrices, which
// node uses which skin, skeletal (translation / rotation / scale) animation
// channels, and the VRM humanoid head bone.
//
// Broken attribute data (wrong accessor types, NaN) is an error, like any
// other attribute. A skin that cannot be used (a joint that is no node, too
// few or non-finite inverse bind matrices, a vertex naming a joint the skin
// does not have) is dropped with a warning and its meshes draw unskinned,
// Filament-style: the rest of the model is still fine. Errors returned here
// do not name the file; the loader prefixes it.
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "engine/core/result.h"
#include "engine/scene/gltf_accessor_reader.h"
#include "engine/scene/model.h"

namespace eng {

// Fills out.joints / out.jointWeights from JOINTS_n / WEIGHTS_n (n = 0, 1, ...
// while both exist), weights renormalised to sum 1 per vertex. `label` names
// the primitive in messages.
Result<void> readSkinAttributes(GltfAccessorReader& reader, const tinygltf::Model& gltf, const tinygltf::Primitive& src,
                                const std::string& label, Primitive& out, std::vector<std::string>& warnings);

// Reads gltf.skins into model.skins and sets Node::skin; model.nodes and
// model.meshes must be loaded. Also reads the VRM humanoid head bone.
Result<void> readSkins(GltfAccessorReader& reader, const tinygltf::Model& gltf, Model& model);

// Reads translation / rotation / scale channel `c` of `src` into
// anim.nodeChannels. A channel that cannot be used (bad node, sampler, key
// count, unsorted times) is skipped with a warning.
Result<void> readNodeChannel(GltfAccessorReader& reader, const tinygltf::Animation& src, size_t c,
                             const std::string& label, Model& model, Animation& anim);

}  // namespace eng
