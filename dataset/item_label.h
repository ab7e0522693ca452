#pragma once
// One line of labels.jsonl: everything a model trained on the image may
// learn from, in the image's own terms (pixels, the camera that drew it):
//
//   {"index": 12, "image": "images/000012.png", "model": "head", "emotion": "happy",
//    "intensity": 0.81, "actionUnits": {"AU6_CheekRaiser": 0.61, ...},
//    "targets": {"AU6_CheekRaiser": 0.61, ...}, "landmarks68": [[x, y], ... 68],
//    "faceBox": [x0, y0, x1, y1], "headPose": {"yaw": 12.5, "pitch": -3.1, "roll": 0},
//    "light": {"rig": "left", ...}, "background": "studio", "camera": {...}}
//
// Numbers are rounded (pixels to 1/100, weights to 1/10000) so the text is
// short and the same on every machine.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "dataset/landmark_tracker.h"
#include "engine/view/camera.h"

namespace dataset {

struct ItemLabel {
  uint64_t index = 0;
  std::string image;  // relative to the dataset folder
  std::string model, emotion;
  float intensity = 0.0f;
  std::vector<std::pair<std::string, float>> actionUnits;  // non-zero ones, channel order
  std::vector<std::pair<std::string, float>> targets;      // non-zero ones, the model's order
  Landmarks2 landmarks{};
  std::string light, background;
  eng::OrbitCamera camera;
  uint32_t width = 0, height = 0;
};

// "images/000012.png": at least six digits, more when the dataset needs them.
std::string imageName(uint64_t index, uint64_t count);
std::string labelName(uint64_t index, uint64_t count);  // "labels/000012.json"

// The smallest box holding the 68 points: {x0, y0, x1, y1}.
std::array<float, 4> faceBox(const Landmarks2& landmarks);

// One JSON object, no newline.
std::string labelJson(const ItemLabel& label);

}  // namespace dataset
