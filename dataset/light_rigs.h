#pragma once
// The light rigs a dataset varies over, by name: the studio rig the programs
// use (eng::vk::LightRig's defaults) and variations of where the key light
// stands and how hard it is, so a model trained on the images does not learn
// one lighting.
#include <optional>
#include <span>
#include <string_view>

#include "engine/vk/draw/light_rig.h"

namespace dataset {

struct NamedLightRig {
  std::string_view name;
  std::string_view description;
  eng::vk::LightRig rig;
};

std::span<const NamedLightRig> lightRigs();
const NamedLightRig* findLightRig(std::string_view name);

}  // namespace dataset
