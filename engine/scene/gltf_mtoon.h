#pragma once
// MToon, the toon material of VRM avatars (VRoid Studio), read into
// eng::ToonShading: VRM 1.0's VRMC_materials_mtoon on a material, or VRM
// 0.x's materialProperties entry (shader "VRM/MToon") for the material of the
// same index, converted the way UniVRM migrates 0.x files to 1.0. Drawn: the
// shade colour (and a shade texture, by the base colour's texture), the
// shading shift and toony width (and its texture), GI equalization, the
// parametric rim and matcap (and the rim's mask), the outline (and its width
// mask). Not drawn: UV animation, 0.x's shading grade texture.
#include <optional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "engine/scene/model.h"

namespace eng {

inline constexpr const char* kVrmcMaterialsMtoon = "VRMC_materials_mtoon";

struct MtoonRead {
  std::optional<ToonShading> toon;
  // The glTF texture the shade colour is multiplied by (-1: none), so the
  // caller can say when the base colour's texture stands in for it.
  int shadeTexture = -1;
  // VRM 0.x's normal map (`_BumpMap`, -1: none) and its `_BumpScale`: the
  // caller draws it where the glTF material has no normalTexture of its own.
  int normalTexture = -1;
  float normalScale = 1.0f;
  // The matcap (1.0's matcapTexture, 0.x's _SphereAdd; -1: none).
  int matcapTexture = -1;
  // The masks read through UVs (index -1: none): 1.0's shadingShiftTexture,
  // rimMultiplyTexture and outlineWidthMultiplyTexture; 0.x's _RimTexture and
  // _OutlineWidthTexture (as UniVRM migrates them: 0.x read the outline
  // width from red, 1.0 from green; a grey mask, as painted, reads the same).
  struct Texture {
    int index = -1;
    int texCoord = 0;
    tinygltf::ExtensionMap extensions;  // KHR_texture_transform
  };
  Texture shadingShiftTexture, rimMultiplyTexture, outlineWidthTexture;
  // One line each for values out of range or of the wrong type (kept at
  // their defaults) and for the parts of MToon that are not drawn.
  std::vector<std::string> problems;
};

// The MToon parameters of material `index` of `gltf`, if it has any. VRM
// 1.0's extension wins over a 0.x entry for the same material.
MtoonRead readMtoon(const tinygltf::Model& gltf, size_t index);

}  // namespace eng
