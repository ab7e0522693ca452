#include "dataset/landmark_overlay.h"

#include <algorithm>
#include <cmath>

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

void drawDot(eng::Image& image, glm::vec2 centre, int radius, glm::u8vec4 colour) {
  const glm::ivec2 c = glm::ivec2(glm::floor(centre));
  for (int y = c.y - radius; y <= c.y + radius; ++y)
    for (int x = c.x - radius; x <= c.x + radius; ++x) {
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      if ((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) > radius * radius) continue;
      uint8_t* p = &image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
      p[0] = colour.r, p[1] = colour.g, p[2] = colour.b, p[3] = 255;
    }
}

}  // namespace

void drawLandmarks(eng::Image& image, const Landmarks2& landmarks) {
  const int radius = std::max(1, std::min(image.width, image.height) / 200);
  for (size_t i = 0; i < landmarks.size(); ++i) drawDot(image, landmarks[i], radius, colourOf(i));
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
