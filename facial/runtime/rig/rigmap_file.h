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
//      "AU45_Blink_L": [{"target": "EyeClose_L", "weight": 1.0}]},
//    "visemes": {                          (optional: lip sync)
//      "aa": {"MouthOpen": 1.0}, "PP": {"MouthClose": 1.0},
//      "jawOpen": {"JawDown": 1.0}},
//    "calibration": {"AU12_LipCornerPuller_L": 1.2}}  (optional)
//
// "calibration" scales action units on top of the measured per-rig
// calibration (rig_calibration.h), factors in [0, 4]. A file with a
// calibration and no map tunes the scheme detected from the target names
// (e.g. data/rigmaps/facecap.json for an ARKit face).
//
// Keys of "map" are action-unit channel names (actionUnits()) or emotion
// names (emotionNames()); weights are finite numbers in [-1, 1]; a target
// must exist in the model (every target of that name is driven). Errors name
// the file, the JSON path and the problem.
//
// Keys of "visemes" are the 15 Oculus visemes (sil PP FF TH DD kk CH SS nn RR
// aa E I O U, any spelling rigVisemeIndex reads) or the three mouth channels
// (jawOpen, lipClosure, lipRounding), each {target: weight in [-1, 1]}. A
// mouth channel drives its target by every viseme's mouth shape
// (mouthShapeOf; sil, the relaxed mouth, drives nothing), so a face with only
// a jaw-open target speaks with one line. Keys add up. A file with "visemes"
// and no "map" drives only the mouth. Without "visemes" the block comes from
// the names and rows as detection would give it (mapSpeech).
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/result.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

struct RigMapFile {
  std::optional<RigMapping> mapping;  // absent: the file only calibrates the detected scheme
  std::vector<std::pair<std::string, float>> calibration;
};

eng::Result<RigMapFile> loadRigMapFile(const std::filesystem::path& file, std::span<const std::string> targetNames);
// The mapping of a file that has one ("/map missing" otherwise).
eng::Result<RigMapping> loadRigMap(const std::filesystem::path& file, std::span<const std::string> targetNames);
eng::Result<RigMapping> parseRigMap(std::string_view json, std::string_view source,
                                    std::span<const std::string> targetNames);

}  // namespace facial
