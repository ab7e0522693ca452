#include "autorig/landmark_detector.h"

#include <cmath>
#include <map>
#include <mutex>
#include <string>

#include <dlib/image_processing.h>
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
  dlib::array2d<dlib::rgb_pixel> pixels = toDlib(image);
  std::vector<dlib::rect_detection> found;
  {
    std::lock_guard lock(impl_->mutex);
    impl_->detector(pixels, found, 0.0);
  }
  if (found.empty()) return std::nullopt;
  const dlib::rect_detection* best = &found[0];
  for (const dlib::rect_detection& d : found)
    if (d.detection_confidence > best->detection_confidence) best = &d;
  return fitShape(impl_->predictor, pixels, best->rect, float(best->detection_confidence));
}

DetectedFace LandmarkDetector::fit(const eng::Image& image, const PixelBox& box) const {
  if (!usable(image)) return {};
  dlib::array2d<dlib::rgb_pixel> pixels = toDlib(image);
  dlib::rectangle rect(long(std::lround(box.min.x)), long(std::lround(box.min.y)), long(std::lround(box.max.x)) - 1,
                       long(std::lround(box.max.y)) - 1);
  return fitShape(impl_->predictor, pixels, rect, std::nanf(""));
}

}  // namespace autorig
