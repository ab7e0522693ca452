#pragma once
// A pose of a model's node hierarchy: every node's local translation,
// rotation and scale, sampled from skeletal animation channels (glTF
// STEP / LINEAR / CUBICSPLINE) or set by hand (idle head motion), and the
// world (model-space) matrices and skin joint matrices derived from it.
// Flat arrays indexed by node, like Model::nodes.
//
//   eng::Pose pose = eng::restPose(model);
//   eng::sampleAnimation(model.animations[0], t, pose);
//   eng::poseWorldMatrices(model, pose, world);
//   eng::skinJointMatrices(model, skin, world, meshNode, joints);
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/model.h"

namespace eng {

struct Pose {
  std::vector<glm::vec3> translations;
  std::vector<glm::quat> rotations;
  std::vector<glm::vec3> scales;
  // Nodes given as a matrix (Node::hasMatrix) keep it: glTF forbids animating them.

  size_t nodeCount() const { return translations.size(); }
};

// The nodes of the default scene that draw a mesh, depth first from
// Model::roots (children in order), each once: the draw order of the renderer.
std::vector<int> sceneMeshNodeIndices(const Model& model);

// Every node's own TRS (the bind / rest pose).
Pose restPose(const Model& model);

// Sets the nodes the animation's TRS channels target to their value at
// `time` (clamped to each channel's keys); other nodes keep theirs. Weights
// channels are not touched (the facial runtime drives those).
void sampleAnimation(const Animation& animation, float time, Pose& pose);

// The local matrix of `node` in `pose` (Node::matrix for matrix nodes).
glm::mat4 poseLocalMatrix(const Model& model, const Pose& pose, int node);

// World (model-space) matrix of every node, parents first; out is resized to
// the node count. pose.nodeCount() must equal model.nodes.size().
void poseWorldMatrices(const Model& model, const Pose& pose, std::vector<glm::mat4>& out);

// poseWorldMatrices of the rest pose: every node's world matrix in one pass
// over the hierarchy. Use it, not Model::worldTransform per node, wherever
// many nodes are placed (that walks to the root each time: O(nodes x depth),
// and a chain of nodes never finished).
std::vector<glm::mat4> restWorldMatrices(const Model& model);

// Whether a transform's linear part can be inverted, judged against its own
// size (Hadamard's bound: |det| <= the product of the column lengths), not an
// absolute threshold: facecap's skin sits under scales of about 2e-5 per axis
// (a determinant near 1e-14), which is a face, not a collapsed node.
bool isInvertible(const glm::mat3& linear);

// The matrices that move a skinned vertex from the bind pose into the space
// of the mesh node that draws it: inverse(world[meshNode]) * world[joint] *
// inverseBind (the glTF formulation; the mesh node's own transform then
// places the result, so skinned and rigid primitives of one node share it).
// out is resized to skin.joints.size().
void skinJointMatrices(const Skin& skin, std::span<const glm::mat4> world, int meshNode, std::vector<glm::mat4>& out);

}  // namespace eng
