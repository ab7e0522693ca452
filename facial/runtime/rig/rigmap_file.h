#pragma once
// Hand-written rig maps for models whose target names match no built-in
// scheme (data/rigmaps/<model>.json):
//
//   {"version": 1,
//    "model": "RobotExpressive",          (optional, informational)
//    "description": "...",                (optional)
//    "weightRange": [0, 1],               (optional, default [0, 1])
//    "map": {
//      "anger":        [{"target": "Angry", "weight": 1.0}],
//      "AU45_Blink_L": [{"target": "EyeClose_L", "weight": 1.0}]}}
//
// Keys of "map" are action-unit channel names (actionUnits()) or emotion
// names (emotionNames()); weights are finite numbers in [-1, 1]; a target
// must exist in the model (every target of that name is driven). Errors name
// the file, the JSON path and the problem.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/result.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

eng::Result<RigMapping> loadRigMap(const std::filesystem::path& file, std::span<const std::string> targetNames);
eng::Result<RigMapping> parseRigMap(std::string_view json, std::string_view source,
                                    std::span<const std::string> targetNames);

}  // namespace facial
