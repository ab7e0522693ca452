#include "autorig/landmark_detector.h"

#include <cmath>
#include <map>
#include <mutex>
#include <string>

#include <dlib/image_processing.h>
#include <dlib/image_transforms.h>
#include <dlib/image_processing/frontal_face_detector.h>
#include <dlib/serialize.h>

namespace autorig {

struct LandmarkDetector::Impl {
  // The HOG detector keeps scratch buffers: one caller at a time.
  mutable std::mutex mutex;
  mutable dlib::frontal_face_detector detector = dlib::get_frontal_face_detector();
  dlib::shape_predictor predictor;
};

LandmarkDetector::LandmarkDetector(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LandmarkDetector::~LandmarkDetector() = default;

namespace {

dlib::array2d<dlib::rgb_pixel> toDlib(const eng::Image& image) {
  dlib::array2d<dlib::rgb_pixel> out(image.height, image.width);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = &image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
      out[y][x] = dlib::rgb_pixel(p[0], p[1], p[2]);
    }
  return out;
}

DetectedFace fitShape(const dlib::shape_predictor& predictor, const dlib::array2d<dlib::rgb_pixel>& image,
                      const dlib::rectangle& box, float confidence) {
  dlib::full_object_detection shape = predictor(image, box);
  DetectedFace face;
  for (size_t i = 0; i < kLandmarkCount && i < shape.num_parts(); ++i)
    face.pixels[i] = glm::vec2(float(shape.part(i).x()) + 0.5f, float(shape.part(i).y()) + 0.5f);
  face.box = {{float(box.left()), float(box.top())}, {float(box.right() + 1), float(box.bottom() + 1)}};
  face.confidence = confidence;
  return face;
}

bool usable(const eng::Image& image) {
  return image.width > 0 && image.height > 0 && image.rgba8.size() == size_t(image.width) * size_t(image.height) * 4;
}

// The most confident face dlib's detector finds in `pixels`, its points fitted.
std::optional<DetectedFace> detectIn(const LandmarkDetector::Impl& impl, const dlib::array2d<dlib::rgb_pixel>& pixels) {
  std::vector<dlib::rect_detection> found;
  {
    std::lock_guard lock(impl.mutex);
    impl.detector(pixels, found, 0.0);
  }
  if (found.empty()) return std::nullopt;
  const dlib::rect_detection* best = &found[0];
  for (const dlib::rect_detection& d : found)
    if (d.detection_confidence > best->detection_confidence) best = &d;
  return fitShape(impl.predictor, pixels, best->rect, float(best->detection_confidence));
}

}  // namespace

eng::Result<std::shared_ptr<const LandmarkDetector>> LandmarkDetector::shared(const std::filesystem::path& predictor) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const LandmarkDetector>> loaded;
  std::lock_guard lock(mutex);
  if (auto it = loaded.find(predictor.string()); it != loaded.end()) return it->second;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(predictor, ec))
    return eng::makeError(eng::ErrorKind::NotFound,
                          predictor.string() + ": no such file (dlib's 68-point shape predictor; Debian libdlib-data)");
  auto impl = std::make_unique<Impl>();
  try {
    dlib::deserialize(predictor.string()) >> impl->predictor;
  } catch (const std::exception& e) {
    return eng::makeError(eng::ErrorKind::Malformed,
                          predictor.string() + ": not a dlib shape predictor (" + std::string(e.what()).substr(0, 120) + ")");
  }
  if (impl->predictor.num_parts() != kLandmarkCount)
    return eng::makeError(eng::ErrorKind::Malformed, predictor.string() + ": the shape predictor has " +
                                                           std::to_string(impl->predictor.num_parts()) +
                                                           " points, not the 68 of iBUG 300-W");
  auto detector = std::make_shared<const LandmarkDetector>(std::move(impl));
  loaded.emplace(predictor.string(), detector);
  return detector;
}

std::optional<DetectedFace> LandmarkDetector::detect(const eng::Image& image) const {
  if (!usable(image)) return std::nullopt;
  const dlib::array2d<dlib::rgb_pixel> pixels = toDlib(image);
  std::optional<DetectedFace> face = detectIn(*impl_, pixels);
  if (!face) return std::nullopt;
  // dlib's detector finds faces rolled up to about 45° in the picture, but
  // its predictor places a rolled face's outline poorly (the built-in head
  // rolled 45°: jaw-line points 0.44 eye spans off). A face rolled more than
  // kLevelRollSlackDegrees is looked at again in the picture turned to level
  // its eyes, and the points are turned back.
  const glm::vec2 eyeLine = face->pixels[45] - face->pixels[36];
  const double roll = std::atan2(double(eyeLine.y), double(eyeLine.x));
  if (std::abs(roll) <= glm::radians(double(kLevelRollSlackDegrees))) return face;
  dlib::array2d<dlib::rgb_pixel> level;
  const dlib::point_transform_affine toLevel = dlib::rotate_image(pixels, level, roll);
  std::optional<DetectedFace> levelled = detectIn(*impl_, level);
  if (!levelled) return face;
  const dlib::point_transform_affine back = dlib::inv(toLevel);
  auto turnedBack = [&](glm::vec2 p) {
    const dlib::dpoint q = back(dlib::dpoint(double(p.x) - 0.5, double(p.y) - 0.5));
    return glm::vec2(float(q.x()) + 0.5f, float(q.y()) + 0.5f);
  };
  const glm::vec2 levelLine = levelled->pixels[45] - levelled->pixels[36];
  if (std::abs(std::atan2(levelLine.y, levelLine.x)) > std::abs(roll)) return face;  // not levelled after all
  for (glm::vec2& p : levelled->pixels) p = turnedBack(p);
  PixelBox box{glm::vec2(INFINITY), glm::vec2(-INFINITY)};
  for (const glm::vec2 corner : {levelled->box.min, levelled->box.max, glm::vec2(levelled->box.min.x, levelled->box.max.y),
                                 glm::vec2(levelled->box.max.x, levelled->box.min.y)}) {
    const glm::vec2 p = turnedBack(corner);
    box.min = glm::min(box.min, p), box.max = glm::max(box.max, p);
  }
  levelled->box = box;
  return levelled;
}

DetectedFace LandmarkDetector::fit(const eng::Image& image, const PixelBox& box) const {
  if (!usable(image)) return {};
  dlib::array2d<dlib::rgb_pixel> pixels = toDlib(image);
  dlib::rectangle rect(long(std::lround(box.min.x)), long(std::lround(box.min.y)), long(std::lround(box.max.x)) - 1,
                       long(std::lround(box.max.y)) - 1);
  return fitShape(impl_->predictor, pixels, rect, std::nanf(""));
}

}  // namespace autorig
