#include "dataset/light_rigs.h"

#include <array>

namespace dataset {
namespace {

eng::vk::LightRig withKey(float azimuth, float elevation, float intensity, float fill) {
  eng::vk::LightRig rig;
  rig.key.azimuthDegrees = azimuth;
  rig.key.elevationDegrees = elevation;
  rig.key.intensity = intensity;
  rig.fill.azimuthDegrees = -azimuth * 1.5f;
  rig.fill.intensity = fill;
  return rig;
}

const std::array<NamedLightRig, 6>& rigs() {
  static const std::array<NamedLightRig, 6> kRigs{{
      {"studio", "the programs' three-point rig: warm key upper left, cool fill, rim", eng::vk::LightRig{}},
      {"soft", "a low-contrast rig: key and fill close in strength", withKey(-20.0f, 30.0f, 1.0f, 0.7f)},
      {"left", "hard key from the camera's left side", withKey(-70.0f, 20.0f, 1.5f, 0.1f)},
      {"right", "hard key from the camera's right side", withKey(70.0f, 20.0f, 1.5f, 0.1f)},
      {"top", "key from high above (deep eye sockets)", withKey(0.0f, 75.0f, 1.5f, 0.15f)},
      {"low", "key from below the face", withKey(10.0f, -35.0f, 1.3f, 0.2f)},
  }};
  return kRigs;
}

}  // namespace

std::span<const NamedLightRig> lightRigs() { return rigs(); }

const NamedLightRig* findLightRig(std::string_view name) {
  for (const NamedLightRig& rig : rigs())
    if (rig.name == name) return &rig;
  return nullptr;
}

}  // namespace dataset
