#pragma once
// Radial basis function interpolation of control-point displacements
// (the study's RBF deformation). Solving is factored once per control-point
// layout; afterwards any displacement field maps to coefficients, and a baked
// RbfEvaluator turns displacements into displacements of a fixed point set
// (mesh vertices) as one dense linear map.
#include <span>
#include <vector>

#include <Eigen/Dense>
#include <glm/glm.hpp>

#include "engine/core/result.h"

namespace facial {

enum class RbfKernelType {
  Biharmonic,    // phi(r) = r
  Polyharmonic,  // phi(r) = r^(2k+1), k >= 1 (k = 1: r^3, "triharmonic")
  Multiquadric,  // phi(r) = sqrt(r^2 + c^2)
};

struct RbfKernel {
  RbfKernelType type = RbfKernelType::Biharmonic;
  int k = 1;        // Polyharmonic exponent 2k+1
  float c = 0.1f;   // Multiquadric shape parameter (same units as positions)
  double operator()(double r) const;
};

// Per-point falloff: weight in [0,1] multiplied into the interpolated
// displacement so an action unit stays local to its region.
using FalloffMask = std::span<const float>;

// Factored RBF system for one control-point layout:
//   f(x) = sum_i w_i phi(|x - p_i|) + c0 + c1 x + c2 y + c3 z
// with the side conditions sum w_i = sum w_i p_i = 0 (so affine fields are
// reproduced exactly by every kernel).
class RbfInterpolator {
 public:
  // Fails (message names the sizes / offending indices) on fewer than 4 points,
  // coincident points (closer than `minSeparation`), or a coplanar/degenerate
  // layout that makes the affine term singular.
  static eng::Result<RbfInterpolator> build(std::span<const glm::vec3> controlPoints, const RbfKernel& kernel,
                                             float minSeparation = 1e-6f);

  size_t controlPointCount() const { return points_.size(); }
  const RbfKernel& kernel() const { return kernel_; }

  // Coefficients for one displacement field: (n + 4) x 3 (RBF weights then affine).
  Eigen::MatrixX3d solve(std::span<const glm::vec3> displacements) const;
  glm::vec3 evaluate(const Eigen::MatrixX3d& coefficients, const glm::vec3& x) const;

  // Dense map from control displacements to displacements at `points`
  // (rows = points, cols = control points): bake once, apply per field.
  Eigen::MatrixXd influenceMatrix(std::span<const glm::vec3> points) const;

 private:
  std::vector<glm::dvec3> points_;
  RbfKernel kernel_;
  Eigen::MatrixXd inverseSystem_;  // (n+4) x (n+4) inverse (or factorisation) of the RBF system
};

// Applies a displacement field to a fixed point set through a baked influence
// matrix: out[v] = mask[v] * sum_j M(v, j) * displacement[j].
class RbfDeformer {
 public:
  static eng::Result<RbfDeformer> build(std::span<const glm::vec3> controlPoints, std::span<const glm::vec3> points,
                                         const RbfKernel& kernel);
  // out.size() == points.size(); mask empty or points.size().
  void apply(std::span<const glm::vec3> displacements, std::span<glm::vec3> out, FalloffMask mask = {}) const;
  size_t pointCount() const { return static_cast<size_t>(influence_.rows()); }
  size_t controlPointCount() const { return static_cast<size_t>(influence_.cols()); }

 private:
  Eigen::MatrixXd influence_;
};

}  // namespace facial
