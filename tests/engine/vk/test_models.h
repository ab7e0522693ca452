#pragma once
// Procedural models for the renderer tests (no files needed).
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace vk_test {

struct SphereSpec {
  int rings = 16;
  int segments = 24;
  int targets = 4;          // morph targets with smooth pseudo-random bumps
  bool tangents = false;    // vertex tangents + tangent deltas
  bool normalDeltas = true;
  float radius = 1.0f;
  glm::vec4 color{0.8f, 0.6f, 0.5f, 1.0f};
  bool doubleSided = false;
  eng::AlphaMode alphaMode = eng::AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool unlit = false;       // KHR_materials_unlit
  std::optional<eng::ToonShading> toon;  // MToon
  bool withMaterial = true; // false: the primitive uses the default material
};

// One root node drawing a UV sphere (one mesh, one primitive).
eng::Model makeSphereModel(const SphereSpec& spec);

// Names "t0", "t1", ...
std::string targetName(int index);

}  // namespace vk_test
