#pragma once
// Small procedural meshes shared by test areas (no files needed).
#include <string>

#include "engine/scene/model.h"

namespace testing_support {

// A flat sheet in the XY plane, 1 x 1 centred on the origin, facing +Z:
// side x side vertices (row-major from (-0.5, -0.5)), two triangles per cell,
// no targets, no material.
eng::Primitive flatSheet(int side);

// A model of one node at the origin drawing `mesh`, its only root.
eng::Model singleMeshModel(eng::Mesh mesh, std::string sourcePath = {});

}  // namespace testing_support
