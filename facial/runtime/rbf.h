#pragma once
// Radial basis function interpolation of control-point displacements
// (the study's RBF deformation). Solving is factored once per control-point
// layout; afterwards any displacement field maps to coefficients, and a baked
// RbfDeformer turns displacements into displacements of a fixed point set
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
//
// Internally positions are centred and scaled to a unit box before the system
// is built. Every kernel here is homogeneous up to a constant factor under that
// change (the multiquadric's c is scaled with the positions), so the
// interpolant is the same function; only the conditioning improves.
class RbfInterpolator {
 public:
  // Fails (message names the sizes / offending indices) on fewer than 4 points,
  // non-finite coordinates, an invalid kernel (k < 1, c <= 0), coincident points
  // (closer than `minSeparation`), or a coplanar/collinear layout that makes the
  // affine term singular.
  // `smoothing` (empty, or one per point, >= 0, in the unit box's units)
  // lets the interpolant pass near rather than through a point: a smoothing
  // spline, the energy's weight against that point's misfit.
  static eng::Result<RbfInterpolator> build(std::span<const glm::vec3> controlPoints, const RbfKernel& kernel,
                                             float minSeparation = 1e-6f, std::span<const double> smoothing = {});

  size_t controlPointCount() const { return points_.size(); }
  const RbfKernel& kernel() const { return kernel_; }

  // Coefficients for one displacement field: (n + 4) x 3 (RBF weights then affine),
  // expressed in the interpolator's normalised frame (pass them back to evaluate()).
  // Errors (naming the sizes / the index): displacements.size() != n, a
  // non-finite displacement.
  eng::Result<Eigen::MatrixX3d> solve(std::span<const glm::vec3> displacements) const;
  // Errors: coefficients.rows() != n + 4, a non-finite x.
  eng::Result<glm::vec3> evaluate(const Eigen::MatrixX3d& coefficients, const glm::vec3& x) const;

  // Dense map from control displacements to displacements at `points`
  // (rows = points, cols = control points): bake once, apply per field.
  // Errors (naming the index): a non-finite point.
  eng::Result<Eigen::MatrixXd> influenceMatrix(std::span<const glm::vec3> points) const;

 private:
  // Row [phi(|x - p_0|) ... phi(|x - p_n-1|), 1, x, y, z] for a normalised x.
  using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;
  void basisRow(const glm::dvec3& normalisedX, RowRef row) const;
  glm::dvec3 normalise(const glm::vec3& x) const { return (glm::dvec3(x) - centre_) * invScale_; }

  std::vector<glm::dvec3> points_;  // normalised control points
  RbfKernel kernel_;                // as given by the caller
  RbfKernel normalisedKernel_;      // c scaled into the normalised frame
  glm::dvec3 centre_{0.0};
  double invScale_ = 1.0;
  // LU with partial pivoting of the symmetric indefinite (n+4) x (n+4) system;
  // its reciprocal condition estimate is checked at build.
  Eigen::PartialPivLU<Eigen::MatrixXd> inverseSystem_;
};

// Applies a displacement field to a fixed point set through a baked influence
// matrix: out[v] = mask[v] * sum_j M(v, j) * displacement[j].
// apply() allocates nothing; the matrix is stored row-major in float (one
// contiguous row of n control weights per point) so each output coordinate is
// one vectorised dot product.
class RbfDeformer {
 public:
  static eng::Result<RbfDeformer> build(std::span<const glm::vec3> controlPoints, std::span<const glm::vec3> points,
                                         const RbfKernel& kernel);
  // Wraps an already built interpolator (several point sets can share one layout).
  static eng::Result<RbfDeformer> build(const RbfInterpolator& interpolator, std::span<const glm::vec3> points);

  // out.size() == pointCount(); displacements.size() == controlPointCount();
  // mask empty or pointCount() long. Fails (nothing written) with a message
  // naming the sizes otherwise.
  eng::Result<void> apply(std::span<const glm::vec3> displacements, std::span<glm::vec3> out,
                          FalloffMask mask = {}) const;
  size_t pointCount() const { return static_cast<size_t>(influence_.rows()); }
  size_t controlPointCount() const { return static_cast<size_t>(influence_.cols()); }
  // Influence of control point `control` on point `point`.
  float influence(size_t point, size_t control) const {
    return influence_(static_cast<Eigen::Index>(point), static_cast<Eigen::Index>(control));
  }

 private:
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> influence_;  // points x controls
};

}  // namespace facial
