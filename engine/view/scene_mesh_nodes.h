#pragma once
// The nodes of a model's default scene that draw a mesh, with their world
// transforms: walked depth first from Model::roots (the same walk as
// Model::bounds()), each node once.
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace eng {

struct MeshNode {
  int node = -1;
  int mesh = -1;
  glm::mat4 world{1.0f};  // in the rest pose
  int skin = -1;          // Node::skin: index into Model::skins, -1 = drawn unskinned
};

std::vector<MeshNode> sceneMeshNodes(const Model& model);

}  // namespace eng
