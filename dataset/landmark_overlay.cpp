#include "dataset/landmark_overlay.h"

#include <algorithm>
#include <cmath>

#include "engine/image/canvas.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/image_io.h"

namespace dataset {
namespace {

glm::u8vec4 colourOf(size_t landmark) {
  if (landmark <= 16) return {250, 220, 40, 255};  // jaw
  if (landmark <= 26) return {250, 140, 20, 255};  // brows
  if (landmark <= 35) return {40, 220, 240, 255};  // nose
  if (landmark <= 47) return {40, 230, 60, 255};   // eyes
  return {240, 40, 40, 255};                       // lips
}

}  // namespace

void drawLandmarks(eng::Image& image, const Landmarks2& landmarks) {
  eng::Canvas canvas(image.width, image.height);
  canvas.blit(image.rgba8, image.width, image.height, 0, 0);
  // A square marker centred on each point, clipped by the canvas.
  const int side = std::max(2, std::min(image.width, image.height) / 100);
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const glm::ivec2 corner = glm::ivec2(glm::floor(landmarks[i])) - side / 2;
    canvas.fillRect(corner.x, corner.y, side, side, colourOf(i));
  }
  image.rgba8 = std::move(canvas.rgba);
}

eng::Result<void> makeOverlayFolder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return eng::makeError(eng::ErrorKind::Io, folder.string() + ": cannot create the folder (" + ec.message() + ")");
  return {};
}

eng::Result<void> writeOverlay(eng::Image image, const Landmarks2& landmarks, const std::filesystem::path& path) {
  drawLandmarks(image, landmarks);
  return eng::writeFileWhole(path, [&](const std::filesystem::path& partial) {
    return eng::writePng(partial, image.width, image.height, image.rgba8);
  });
}

}  // namespace dataset
