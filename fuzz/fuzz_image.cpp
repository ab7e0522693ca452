// Texture images as glTF files carry them (PNG, JPEG, BMP, TGA, GIF through
// stb; WebP through libwebp; KTX2 refused by name). A decoded image must be
// exactly width * height RGBA8 pixels.
#include <string>

#include "engine/scene/image_io.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // 4 Mpixel: a forged header must be refused, not decoded into gigabytes.
  auto image = eng::decodeImage({data, size}, "input image", size_t{4} << 20);
  if (image)
    FUZZ_PROPERTY(image->width > 0 && image->height > 0 &&
                      image->rgba8.size() == size_t(image->width) * size_t(image->height) * 4,
                  std::to_string(image->width) + "x" + std::to_string(image->height) + " with " +
                      std::to_string(image->rgba8.size()) + " bytes");
  return 0;
}
