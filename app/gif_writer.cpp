#include "app/gif_writer.h"

#include <cmath>
#include <string>
#include <vector>

#include <cgif.h>
#include <libimagequant.h>

#include "engine/scene/file_bytes.h"

namespace app {

struct GifWriter::Impl {
  std::filesystem::path path;
  std::filesystem::path partialPath;  // written first, renamed to `path` by finish()
  std::string pathString;
  int width = 0, height = 0;
  uint16_t delayCentiseconds = 4;
  float delayError = 0;  // carries the rounding of 1/fps into centiseconds
  float exactDelay = 4;
  CGIF* gif = nullptr;
  liq_attr* attr = nullptr;
  std::vector<uint8_t> indices;
  std::vector<uint8_t> palette;

  ~Impl() {
    if (gif) {
      cgif_close(gif);
      std::error_code ignored;
      std::filesystem::remove(partialPath, ignored);
    }
    if (attr) liq_attr_destroy(attr);
  }
};

GifWriter::GifWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GifWriter::GifWriter(GifWriter&&) noexcept = default;
GifWriter& GifWriter::operator=(GifWriter&&) noexcept = default;
GifWriter::~GifWriter() = default;

eng::Result<GifWriter> GifWriter::create(const std::filesystem::path& path, int width, int height, float fps) {
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535)
    return eng::makeError(eng::ErrorKind::InvalidArgument, path.string() + ": GIF size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is out of range");
  if (!(fps > 0.0f) || !std::isfinite(fps)) return eng::makeError(eng::ErrorKind::InvalidArgument, path.string() + ": GIF frame rate must be positive");
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->pathString = path.string();
  impl->partialPath = impl->pathString + ".partial";
  impl->width = width;
  impl->height = height;
  impl->exactDelay = 100.0f / fps;
  impl->indices.resize(static_cast<size_t>(width) * height);
  impl->palette.resize(256 * 3);
  impl->attr = liq_attr_create();
  if (!impl->attr) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot create the colour quantiser");
  liq_set_speed(impl->attr, 8);  // why: headless tours encode hundreds of frames; 8 is fast and still smooth on skin

  // cgif needs a global palette even when every frame brings its own.
  std::vector<uint8_t> grey(256 * 3);
  for (int i = 0; i < 256; ++i) grey[i * 3] = grey[i * 3 + 1] = grey[i * 3 + 2] = static_cast<uint8_t>(i);
  CGIF_Config config{};
  config.pGlobalPalette = grey.data();
  config.numGlobalPaletteEntries = 256;
  const std::string partial = impl->partialPath.string();
  config.path = partial.c_str();
  config.attrFlags = CGIF_ATTR_IS_ANIMATED;
  config.width = static_cast<uint16_t>(width);
  config.height = static_cast<uint16_t>(height);
  config.numLoops = CGIF_INFINITE_LOOP;
  impl->gif = cgif_newgif(&config);
  if (!impl->gif) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot create GIF file");
  return GifWriter(std::move(impl));
}

eng::Result<void> GifWriter::addFrame(std::span<const uint8_t> rgba8) {
  Impl& s = *impl_;
  if (!s.gif) return eng::makeError(eng::ErrorKind::InvalidArgument, s.pathString + ": GIF already finished");
  const size_t expected = static_cast<size_t>(s.width) * s.height * 4;
  if (rgba8.size() != expected)
    return eng::makeError(eng::ErrorKind::InvalidArgument, s.pathString + ": GIF frame has " + std::to_string(rgba8.size()) + " bytes, expected " +
                     std::to_string(expected));
  liq_image* image = liq_image_create_rgba(s.attr, rgba8.data(), s.width, s.height, 0);
  liq_result* quantised = nullptr;
  if (!image || liq_image_quantize(image, s.attr, &quantised) != LIQ_OK) {
    if (image) liq_image_destroy(image);
    return eng::makeError(eng::ErrorKind::Io, s.pathString + ": colour quantisation failed");
  }
  liq_set_dithering_level(quantised, 0.8f);
  liq_write_remapped_image(quantised, image, s.indices.data(), s.indices.size());
  const liq_palette* pal = liq_get_palette(quantised);
  std::fill(s.palette.begin(), s.palette.end(), 0);
  for (unsigned i = 0; i < pal->count; ++i) {
    s.palette[i * 3 + 0] = pal->entries[i].r;
    s.palette[i * 3 + 1] = pal->entries[i].g;
    s.palette[i * 3 + 2] = pal->entries[i].b;
  }
  CGIF_FrameConfig frame{};
  frame.pLocalPalette = s.palette.data();
  frame.numLocalPaletteEntries = static_cast<uint16_t>(std::max(2u, pal->count));
  frame.attrFlags = CGIF_FRAME_ATTR_USE_LOCAL_TABLE;
  frame.pImageData = s.indices.data();
  // Accumulate rounding so 30 fps averages 3.33 cs per frame instead of drifting.
  const float wanted = s.exactDelay + s.delayError;
  const uint16_t delay = static_cast<uint16_t>(std::max(2.0f, std::round(wanted)));
  s.delayError = wanted - delay;
  frame.delay = delay;
  const int rc = cgif_addframe(s.gif, &frame);
  liq_result_destroy(quantised);
  liq_image_destroy(image);
  if (rc != CGIF_OK) return eng::makeError(eng::ErrorKind::Io, s.pathString + ": writing GIF frame failed (cgif error " + std::to_string(rc) + ")");
  return {};
}

eng::Result<void> GifWriter::finish() {
  Impl& s = *impl_;
  if (!s.gif) return {};
  const int rc = cgif_close(s.gif);
  s.gif = nullptr;
  std::error_code ec;
  if (rc != CGIF_OK) {
    std::filesystem::remove(s.partialPath, ec);
    return eng::makeError(eng::ErrorKind::Io, s.pathString + ": closing GIF failed (cgif error " + std::to_string(rc) + ")");
  }
  return eng::commitPartialFile(s.partialPath, s.path);
}

}  // namespace app
