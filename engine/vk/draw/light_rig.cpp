#include "engine/vk/draw/light_rig.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace eng::vk {

glm::vec3 lightDirection(const OrbitCamera& camera, const DirectionalLight& light) {
  const glm::vec3 toCamera = glm::normalize(camera.position() - camera.target);
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), toCamera));
  const glm::vec3 up = glm::cross(toCamera, right);
  const float az = glm::radians(light.azimuthDegrees);
  const float el = glm::radians(light.elevationDegrees);
  return glm::normalize(toCamera * (std::cos(el) * std::cos(az)) + right * (std::cos(el) * std::sin(az)) +
                        up * std::sin(el));
}

glm::mat4 keyLightViewProj(const OrbitCamera& camera, const glm::vec3& toLight) {
  const float r = camera.sceneRadius * 1.05f;
  const glm::vec3 up = std::abs(toLight.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::mat4 view = glm::lookAtRH(camera.target + toLight * (2.0f * r), camera.target, up);
  return glm::orthoRH_ZO(-r, r, -r, r, 0.0f, 4.0f * r) * view;
}

FrameGlobals buildFrameGlobals(const OrbitCamera& camera, float aspect, const LightRig& rig) {
  FrameGlobals g;
  g.view = camera.view();
  g.proj = camera.projection(aspect);
  g.viewProj = g.proj * g.view;
  g.cameraPosition = glm::vec4(camera.position(), 1.0f);
  g.keyDirection = glm::vec4(lightDirection(camera, rig.key), 0.0f);
  g.keyColor = glm::vec4(rig.key.color * rig.key.intensity, 0.0f);
  g.fillDirection = glm::vec4(lightDirection(camera, rig.fill), 0.0f);
  g.fillColor = glm::vec4(rig.fill.color * rig.fill.intensity, 0.0f);
  g.rimDirection = glm::vec4(lightDirection(camera, rig.rim), 0.0f);
  g.rimColor = glm::vec4(rig.rim.color * rig.rim.intensity, 0.0f);
  g.skyAmbient = glm::vec4(rig.skyAmbient, 0.0f);
  g.groundAmbient = glm::vec4(rig.groundAmbient, 0.0f);
  g.backgroundTop = glm::vec4(rig.backgroundTop, 1.0f);
  g.backgroundBottom = glm::vec4(rig.backgroundBottom, 1.0f);
  g.skin = glm::vec4(rig.diffuseWrap, rig.subsurfaceStrength, rig.specularStrength, rig.exposure);
  g.subsurfaceColor = glm::vec4(rig.subsurfaceColor, 0.0f);
  g.keyLightViewProj = keyLightViewProj(camera, glm::vec3(g.keyDirection));
  // The shadow map spans 2.1 scene radii: a penumbra of softness x radius is this much of its uv range.
  g.shadow = glm::vec4(0.0f, rig.shadowSoftness / 2.1f, camera.sceneRadius * 0.004f, rig.keyShadow ? 1.0f : 0.0f);
  g.shadowColor = glm::vec4(rig.shadowColor, 0.0f);
  return g;
}

}  // namespace eng::vk
