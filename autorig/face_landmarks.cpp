#include "autorig/face_landmarks.h"

#include <cmath>
#include <cstdio>
#include <system_error>

#include "autorig/surface_cast.h"
#include "engine/scene/file_bytes.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/json/json_node.h"

namespace autorig {

namespace {

constexpr size_t kMaxLandmarksFileBytes = size_t{1} << 20;

eng::Result<glm::vec3> readPoint(const facial::JsonNode& node, size_t index) {
  const std::string which = "landmark " + std::to_string(index);
  if (!node.isArray()) return node.error(which + " is not an array of three numbers");
  const size_t size = ENG_TRY_VALUE(node.size());
  if (size != 3) return node.error(which + " has " + std::to_string(size) + " numbers, not 3 (x, y, z)");
  glm::vec3 p;
  for (size_t k = 0; k < 3; ++k) {
    const facial::JsonNode c = node.element(k);
    if (!c.isNumber() || !std::isfinite(c.raw().get<double>())) return c.error(which + " is not three finite numbers");
    p[int(k)] = ENG_TRY_VALUE(c.number());
  }
  return p;
}

eng::Result<FaceLandmarks> readLandmarks(const facial::JsonNode& root) {
  if (!root.isObject()) return root.error("not a landmarks file (an object with \"landmarks68\")");
  const facial::JsonNode points = ENG_TRY_VALUE(root.at("landmarks68"));
  if (!points.isArray()) return points.error("not an array of 68 points");
  const size_t count = ENG_TRY_VALUE(points.size());
  if (count != kLandmarkCount)
    return points.error(std::to_string(count) + " points, not the 68 of the iBUG layout");
  FaceLandmarks landmarks;
  for (size_t i = 0; i < kLandmarkCount; ++i) landmarks.points[i] = ENG_TRY_VALUE(readPoint(points.element(i), i));
  return landmarks;
}

}  // namespace

eng::Result<FaceLandmarks> readLandmarksFile(const std::filesystem::path& path) {
  const facial::Json json = ENG_TRY_VALUE(facial::readJsonFile(path, kMaxLandmarksFileBytes));
  auto landmarks = readLandmarks(facial::JsonNode(json, ""));
  if (!landmarks) return landmarks.error().prefixed(path.string() + ": ");
  landmarks->source = path.string();
  return landmarks;
}

eng::Result<void> writeLandmarksFile(const FaceLandmarks& landmarks, const std::filesystem::path& path) {
  facial::Json points = facial::Json::array();
  for (const glm::vec3& p : landmarks.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return eng::makeError(eng::ErrorKind::InvalidArgument,
                            path.string() + ": landmark " + std::to_string(&p - landmarks.points.data()) +
                                " is not finite; nothing written");
    points.push_back({p.x, p.y, p.z});
  }
  facial::Json json = {{"landmarks68", points}, {"source", landmarks.source}};
  const std::string text = json.dump(1) + "\n";
  return eng::writeFileWhole(path, [&](const std::filesystem::path& partial) {
    return eng::writeFileBytes(partial, text.data(), text.size());
  });
}

eng::Result<void> checkLandmarksOnSurface(const FaceLandmarks& landmarks, const eng::Model& model,
                                          const PosedFace& posed, const std::string& source) {
  const float span = glm::distance(landmarks.points[36], landmarks.points[45]);
  if (!(span > 0.0f))
    return eng::makeError(eng::ErrorKind::Malformed, source + ": landmarks 36 and 45 (the outer eye corners) coincide");
  const float tolerance = kOnSurfaceTolerance * span;
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const float d = distanceToSurface(model, posed, landmarks.points[i]);
    if (d > tolerance) {
      char text[160];
      std::snprintf(text, sizeof text, ": landmark %zu is %.3g from the face's surface (more than %.3g, %g of the eye corners' distance)",
                    i, double(d), double(tolerance), double(kOnSurfaceTolerance));
      return eng::makeError(eng::ErrorKind::Malformed, source + text);
    }
  }
  return {};
}

}  // namespace autorig
