#pragma once
// What a frame looks at and how it is lit.
#include "engine/vk/camera.h"
#include "engine/vk/light_rig.h"

namespace eng::vk {

struct SceneView {
  OrbitCamera camera;
  LightRig lights;
};

}  // namespace eng::vk
