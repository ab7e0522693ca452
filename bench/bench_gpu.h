#pragma once
// One Vulkan context and 256x256 offscreen renderer shared by every GPU
// benchmark of the process (creating them is not what is measured), on
// whatever device Vulkan picks (FACIAL_DEVICE to force one).
#include <memory>
#include <string>

#include "engine/vk/device/context.h"
#include "engine/vk/draw/offscreen_renderer.h"

namespace bench {

struct GpuBench {
  std::unique_ptr<eng::vk::Context> context;
  std::unique_ptr<eng::vk::OffscreenRenderer> renderer;
  std::string error;  // why context or renderer is null
};

GpuBench& gpu();

}  // namespace bench
