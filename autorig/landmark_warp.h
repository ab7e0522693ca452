#pragma once
// The warp that carries the source face onto the target face: a similarity
// (Umeyama: scale, rotation, translation) fitted to landmark pairs, then the
// study's RBF (biharmonic r with the affine term) through the pairs for what
// the similarity leaves (near rather than through the pairs given a
// smoothing weight). Its local Jacobian (central differences) is what
// scales and turns a displacement of the source into one of the target.
#include <span>

#include <Eigen/Dense>
#include <glm/glm.hpp>

#include "engine/core/result.h"
#include "facial/runtime/rbf.h"

namespace autorig {

struct Similarity {
  float scale = 1.0f;
  glm::mat3 rotation{1.0f};
  glm::vec3 translation{0.0f};
  glm::vec3 apply(const glm::vec3& p) const { return scale * (rotation * p) + translation; }
};

// Least squares similarity source -> target (Umeyama 1991). Errors: sizes
// differ or fewer than 3 pairs, either set collapsed to a point or a line,
// the best fit needs a mirror (the target's points are the source's seen
// mirrored: left and right swapped).
eng::Result<Similarity> fitSimilarity(std::span<const glm::vec3> source, std::span<const glm::vec3> target);

class LandmarkWarp {
 public:
  // `minSeparation` (world units of the source): pairs whose source points
  // are closer are refused by the RBF (errors name them). `smoothing` (empty
  // or one per pair): RbfInterpolator::build's, how near rather than through
  // each pair the bend passes. The RBF's points
  // are the source's carried onto the target by the similarity, so the bound
  // is scaled with them: a face a thousandth the source's size is not refused.
  static eng::Result<LandmarkWarp> build(std::span<const glm::vec3> source, std::span<const glm::vec3> target,
                                         float minSeparation = 1e-6f, std::span<const double> smoothing = {});

  glm::vec3 apply(const glm::vec3& p) const;
  // d apply / d p at p, by central differences of `step` (world units of the source).
  glm::mat3 jacobian(const glm::vec3& p, float step) const;
  const Similarity& similarity() const { return similarity_; }
  // Root mean square distance between the similarity-moved source points and
  // their targets: how much of the fit the RBF had to bend.
  float similarityResidual() const { return residual_; }

 private:
  LandmarkWarp(Similarity similarity, facial::RbfInterpolator rbf, Eigen::MatrixX3d coefficients, float residual)
      : similarity_(similarity), rbf_(std::move(rbf)), coefficients_(std::move(coefficients)), residual_(residual) {}
  Similarity similarity_;
  facial::RbfInterpolator rbf_;
  Eigen::MatrixX3d coefficients_;
  float residual_ = 0.0f;
};

}  // namespace autorig
