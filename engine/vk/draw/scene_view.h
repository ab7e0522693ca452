#pragma once
// What a frame looks at and how it is lit.
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/view/camera.h"
#include "engine/vk/draw/light_rig.h"

namespace eng::vk {

// What lies behind the models. Transparent renders for compositing: alpha is
// the MSAA coverage, and the read-back colour is un-premultiplied, so edges
// carry the model's own colour (no dark fringe over a bright background).
struct Backdrop {
  enum class Kind : uint8_t { Studio, Solid, Transparent };
  Kind kind = Kind::Studio;  // Studio: the soft gradient of background.frag
  glm::vec3 srgb{0.0f};      // Solid: the colour, sRGB-encoded [0,1]
};

struct SceneView {
  OrbitCamera camera;
  LightRig lights;
  Backdrop backdrop;
};

}  // namespace eng::vk
