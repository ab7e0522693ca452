#pragma once
// Small procedural meshes shared by test areas (no files needed).
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace testing_support {

// A flat sheet in the XY plane, 1 x 1 centred on the origin, facing +Z:
// side x side vertices (row-major from (-0.5, -0.5)), two triangles per cell,
// no targets, no material.
eng::Primitive flatSheet(int side);

// A model of one node at the origin drawing `mesh`, its only root.
eng::Model singleMeshModel(eng::Mesh mesh, std::string sourcePath = {});

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

// The sphere's target names: "t0", "t1", ...
std::string targetName(int index);

// An untextured white sphere with `targets` bumps (plaster, as faces without
// textures come).
SphereSpec whiteSphereSpec(int targets);

// Adds `part` (a one-mesh model such as a sphere) to `model` as a root node
// `name` at `at`, scaled by `scale`, with its materials.
void addPartAsRoot(eng::Model& model, eng::Model part, const std::string& name, glm::vec3 at, glm::vec3 scale);

// A plaster head: a unit sphere "head" with two targets, two untextured
// eyeballs "eyeLeft" / "eyeRight" (radius 0.12 at (+-0.35, 0.2, 0.85)) and
// "teeth" at (0, -0.4, 0.8); one mesh per node, in that order.
eng::Model plasterHead();

// The model without any morph target (nor the animations that weight them):
// a face to rig, as scans and sculpts come.
eng::Model stripped(eng::Model model);

// Every primitive of `model` as a triangle soup: each corner its own vertex,
// as three.js's GLTFExporter writes a non-indexed geometry (an OBJ it read).
eng::Model asTriangleSoup(eng::Model model);
// The soup of `model` flat-shaded: each corner's normal its triangle's (a
// low-poly character, an export with every edge hard).
eng::Model asFlatShaded(const eng::Model& model);

}  // namespace testing_support
