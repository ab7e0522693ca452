#pragma once
// Reference CPU skinning (linear blend skinning, as glTF, three.js and the
// GPU path do it): after morphing, each vertex moves by the weighted sum of
// its joints' matrices, p' = (sum_i w_i * J[j_i]) p, and its normal by the
// upper 3x3 of the same sum, renormalised. Tests check the GPU path against
// it; posed bounds and picking use it.
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// The blended skin matrix of vertex `vertex` (identity when its weights sum
// to zero; influences naming a joint past jointMatrices are skipped).
glm::mat4 vertexSkinMatrix(const Primitive& primitive, size_t vertex, std::span<const glm::mat4> jointMatrices);

// Skins morphed vertices in place (positions, and normals unless empty), a
// job over spans like MorphPrimitiveJob: Run() validates first and returns
// false, touching nothing, when Validate() names a problem.
// jointMatrices: eng::skinJointMatrices of the skin of the node drawing the
// primitive. A primitive without joints is left unchanged.
struct SkinPrimitiveJob {
  const Primitive* primitive = nullptr;
  std::span<const glm::mat4> jointMatrices;
  std::span<glm::vec3> positions;  // vertexCount long
  std::span<glm::vec3> normals;    // empty, or vertexCount long
  Result<void> Validate() const;
  bool Run() const;
};

// SkinPrimitiveJob{&primitive, jointMatrices, positions, normals}.Run().
bool skinPrimitiveCpu(const Primitive& primitive, std::span<const glm::mat4> jointMatrices,
                      std::span<glm::vec3> positions, std::span<glm::vec3> normals);

// The CPU counterpart of what the vertex shader does to one primitive of the
// mesh drawn by node `meshNode`: morph by meshWeights (eng::morphPrimitiveCpu),
// then skin by the node's skin (if any) in the pose whose node world matrices
// are `world` (eng::poseWorldMatrices). The result is in the node's own space,
// the space of the GPU capture; world[meshNode] places it. False (positions
// and normals untouched) when the morph or skin job does not validate.
bool posePrimitiveCpu(const Model& model, int meshNode, const Primitive& primitive, std::span<const float> meshWeights,
                      std::span<const glm::mat4> world, std::span<glm::vec3> positions, std::span<glm::vec3> normals);

}  // namespace eng
