#include "dataset/item_label.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "dataset/light_rigs.h"

namespace dataset {
namespace {

// Divided by the power of ten (not times its inverse): the nearest double to
// the decimal, so the text is "0.2935", never "0.29350000000000004".
double rounded(double value, double scale) { return std::round(value * scale) / scale; }
double pixel(float value) { return rounded(value, 100.0); }
double weight(float value) { return rounded(value, 10000.0); }

std::string numbered(const char* folder, uint64_t index, uint64_t count, const char* extension) {
  int digits = 6;
  for (uint64_t last = count > 0 ? count - 1 : 0; last >= 1000000; last /= 10) ++digits;
  std::string number = std::to_string(index);
  if (number.size() < size_t(digits)) number.insert(0, size_t(digits) - number.size(), '0');
  return std::string(folder) + "/" + number + "." + extension;
}

nlohmann::ordered_json weightObject(const std::vector<std::pair<std::string, float>>& weights) {
  nlohmann::ordered_json object = nlohmann::ordered_json::object();
  for (const auto& [name, value] : weights) object[name] = weight(value);
  return object;
}

nlohmann::ordered_json vec3Json(const glm::vec3& v) { return {weight(v.x), weight(v.y), weight(v.z)}; }

nlohmann::ordered_json lightJson(const std::string& name) {
  const NamedLightRig* rig = findLightRig(name);
  nlohmann::ordered_json light{{"rig", name}};
  if (!rig) return light;
  light["keyAzimuth"] = rig->rig.key.azimuthDegrees;
  light["keyElevation"] = rig->rig.key.elevationDegrees;
  light["keyIntensity"] = weight(rig->rig.key.intensity);
  light["fillIntensity"] = weight(rig->rig.fill.intensity);
  return light;
}

nlohmann::ordered_json cameraJson(const ItemLabel& label) {
  const eng::OrbitCamera& c = label.camera;
  return {{"yaw", weight(c.yawDegrees)},   {"pitch", weight(c.pitchDegrees)}, {"zoom", weight(c.zoom)},
          {"fovY", weight(c.fovYDegrees)}, {"position", vec3Json(c.position())}, {"target", vec3Json(c.target)},
          {"width", label.width},          {"height", label.height}};
}

}  // namespace

std::string imageName(uint64_t index, uint64_t count) { return numbered("images", index, count, "png"); }
std::string labelName(uint64_t index, uint64_t count) { return numbered("labels", index, count, "json"); }

std::array<float, 4> faceBox(const Landmarks2& landmarks) {
  std::array<float, 4> box{landmarks[0].x, landmarks[0].y, landmarks[0].x, landmarks[0].y};
  for (const glm::vec2& p : landmarks) {
    box[0] = std::min(box[0], p.x), box[1] = std::min(box[1], p.y);
    box[2] = std::max(box[2], p.x), box[3] = std::max(box[3], p.y);
  }
  return box;
}

std::string labelJson(const ItemLabel& label) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const glm::vec2& p : label.landmarks) points.push_back({pixel(p.x), pixel(p.y)});
  const std::array<float, 4> box = faceBox(label.landmarks);
  nlohmann::ordered_json j{
      {"index", label.index},
      {"image", label.image},
      {"model", label.model},
      {"emotion", label.emotion},
      {"intensity", weight(label.intensity)},
      {"actionUnits", weightObject(label.actionUnits)},
      {"targets", weightObject(label.targets)},
      {"landmarks68", std::move(points)},
      {"faceBox", {pixel(box[0]), pixel(box[1]), pixel(box[2]), pixel(box[3])}},
      // The camera orbits a still head, so the head's pose in the camera's
      // frame is the orbit's: yaw + shows more of the subject's left cheek,
      // pitch + looks from above; the camera never rolls.
      {"headPose", {{"yaw", weight(label.camera.yawDegrees)}, {"pitch", weight(label.camera.pitchDegrees)}, {"roll", 0}}},
      {"light", lightJson(label.light)},
      {"background", label.background},
      {"camera", cameraJson(label)},
  };
  return j.dump();
}

}  // namespace dataset
