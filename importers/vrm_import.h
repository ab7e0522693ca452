#pragma once
// VRM expressions from a glTF document's JSON into the pure runtime
// VrmExpressionSet (vrm_expressions.h):
//  - VRM 1.0: extensions.VRMC_vrm.expressions.{preset, custom}.<name> with
//    morphTargetBinds [{node, index, weight 0..1}], isBinary,
//    overrideBlink / overrideLookAt / overrideMouth ("none" | "block" | "blend");
//  - VRM 0.x: extensions.VRM.blendShapeMaster.blendShapeGroups[] with
//    {name, presetName, binds [{mesh, index, weight 0..100}], isBinary}; the
//    expression is called by its presetName unless that is "unknown".
// When both are present VRM 1.0 wins. Flat targets are mesh-major over the
// document's meshes (mesh m's targets at meshTargetOffsets[m]), named
// "<mesh name>/<target name>" from mesh.extras.targetNames ("target_N" without).
// Material colour binds (1.0 materialColorBinds, 0.x materialValues _Color,
// _EmissionColor, ...) and texture transform binds (1.0 textureTransformBinds,
// 0.x _MainTex_ST) address glTF materials by index (0.x: by name); a material
// bind that cannot be applied (no such material, unknown type, a value that is
// not a finite number) is left out with a warning (VrmExpressionSet::warnings)
// naming the source, JSON path and problem. Errors name the same. The lookAt
// (1.0 lookAt, 0.x firstPerson): its type (bone / expression) and range maps,
// for facial::GazeRig.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "engine/core/result.h"
#include "facial/runtime/rig/vrm_expressions.h"

namespace importers {

// A .vrm / .glb (binary container) or a .gltf / .json text document.
eng::Result<facial::VrmExpressionSet> loadVrmExpressions(const std::filesystem::path& file);
eng::Result<facial::VrmExpressionSet> importVrmExpressions(const nlohmann::ordered_json& gltf, std::string_view source);
// The expressions of a glTF / GLB / VRM file, or nullopt when it has no VRM
// extension (a plain glTF). Errors: unreadable file, broken container or JSON, broken VRM data.
eng::Result<std::optional<facial::VrmExpressionSet>> findVrmExpressions(const std::filesystem::path& file);
// The same over the file's bytes, already read; `source` names it in messages.
eng::Result<std::optional<facial::VrmExpressionSet>> findVrmExpressions(std::span<const uint8_t> bytes, std::string_view source);
bool hasVrmExtension(const nlohmann::ordered_json& gltf);

}  // namespace importers
