#pragma once
// The default look for faces: a three-point studio rig (key, fill, rim)
// placed relative to the camera, so the face stays well lit while orbiting,
// plus skin shading parameters and the backdrop. Colours are linear.
#include <glm/glm.hpp>

#include "engine/view/camera.h"
#include "engine/vk/draw/gpu_types.h"

namespace eng::vk {

struct DirectionalLight {
  float azimuthDegrees = 0.0f;    // around the camera's up axis; + = camera's right
  float elevationDegrees = 0.0f;  // + = above
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
};

struct LightRig {
  // Warm key from the upper left of the camera, cool soft fill from the right,
  // rim from behind-above to separate the head from the backdrop.
  DirectionalLight key{-30.0f, 45.0f, {1.0f, 0.95f, 0.88f}, 1.4f};
  DirectionalLight fill{50.0f, 10.0f, {0.80f, 0.88f, 1.0f}, 0.2f};
  DirectionalLight rim{150.0f, 30.0f, {1.0f, 0.97f, 0.94f}, 1.2f};
  glm::vec3 skyAmbient{0.07f, 0.075f, 0.085f};
  glm::vec3 groundAmbient{0.025f, 0.02f, 0.018f};
  float diffuseWrap = 0.15f;                    // 0 = Lambert
  float subsurfaceStrength = 0.55f;              // warm tint at the terminator
  glm::vec3 subsurfaceColor{1.0f, 0.32f, 0.20f};
  float specularStrength = 0.55f;
  // A key-to-fill ratio near 7:1 and an exposure that keeps lit skin below
  // the tone curve's shoulder: the portrait look where brows shade the eye
  // sockets and furrows, lids and lip corners keep their contrast at 256 px
  // (a flatter, brighter rig washed pale faces into a featureless oval).
  float exposure = 0.7f;
  // The key light casts soft shadows (nose, eye sockets, the inside of an open
  // mouth); the other lights do not.
  bool keyShadow = true;
  float shadowSoftness = 0.02f;                  // penumbra radius, fraction of the scene radius
  glm::vec3 shadowColor{0.22f, 0.10f, 0.07f};   // key light left in shadow: warm, as under skin
  glm::vec3 backgroundTop{0.20f, 0.21f, 0.23f};      // linear (~#7c7e83 in sRGB)
  glm::vec3 backgroundBottom{0.045f, 0.047f, 0.052f};
};

// World-space direction toward a light given in camera-relative angles.
glm::vec3 lightDirection(const OrbitCamera& camera, const DirectionalLight& light);

// The key light's orthographic view-projection, fitted around the camera's
// orbit target and scene radius.
glm::mat4 keyLightViewProj(const OrbitCamera& camera, const glm::vec3& toLight);

// Everything the shaders read once per frame.
FrameGlobals buildFrameGlobals(const OrbitCamera& camera, float aspect, const LightRig& rig);

}  // namespace eng::vk
