#include "engine/vk/draw/detail_array.h"

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#define STB_IMAGE_RESIZE_IMPLEMENTATION
#define STB_IMAGE_RESIZE_STATIC  // private copy: no clash with another user of stb_image_resize
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image_resize.h>
#pragma GCC diagnostic pop

#include "engine/vk/draw/texture.h"

namespace eng::vk {

Result<GpuImage> createDetailArray(const Context& ctx, const Model& model, const Material& material) {
  int width = 0;
  int height = 0;
  for (const DetailLayer& layer : material.detailLayers) {
    // checkModel refuses such a model at load; a model built in code gets the same line, not an exception.
    if (layer.image < 0 || static_cast<size_t>(layer.image) >= model.images.size())
      return makeError(ErrorKind::InvalidArgument, "material '" + material.name + "': detail layer image " +
                                                       std::to_string(layer.image) + " of " +
                                                       std::to_string(model.images.size()));
    const eng::Image& img = model.images[static_cast<size_t>(layer.image)];
    width = std::max(width, img.width);
    height = std::max(height, img.height);
  }
  std::vector<std::vector<uint8_t>> resized;  // only the layers that needed it
  resized.reserve(material.detailLayers.size());
  std::vector<std::span<const uint8_t>> layers;
  for (const DetailLayer& layer : material.detailLayers) {
    const eng::Image& img = model.images[static_cast<size_t>(layer.image)];
    if (img.width == width && img.height == height) {
      layers.emplace_back(img.rgba8);
      continue;
    }
    std::vector<uint8_t>& out = resized.emplace_back(size_t(width) * size_t(height) * 4);
    stbir_resize_uint8_srgb(img.rgba8.data(), img.width, img.height, 0, out.data(), width, height, 0, 4, 3, 0);
    layers.emplace_back(out);
  }
  const std::string name = "detail layers of material '" + material.name + "'";
  return createTexture(ctx, {static_cast<uint32_t>(width), static_cast<uint32_t>(height), layers,
                             VK_IMAGE_VIEW_TYPE_2D_ARRAY, name.c_str()});
}

}  // namespace eng::vk
