#include "facial/runtime/rbf.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace facial {
namespace {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 arrays are mapped as packed float triples");

// Below this reciprocal condition estimate the factored system is treated as
// singular: solving it would amplify rounding noise past float precision.
constexpr double kMinReciprocalCondition = 1e-14;
// Relative spread (smallest / largest singular value of the centred layout)
// under which the points count as coplanar or collinear.
constexpr double kMinRelativeSpread = 1e-7;

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

std::string describe(const glm::vec3& p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

// Index of the first point with a non-finite coordinate, or -1.
long firstNonFinite(std::span<const glm::vec3> points) {
  for (size_t i = 0; i < points.size(); ++i)
    if (!finite(points[i])) return static_cast<long>(i);
  return -1;
}

// First pair of points closer than `minSeparation`, found with a sweep over
// the points sorted by x so large layouts stay O(n log n) in practice.
bool findCoincidentPair(std::span<const glm::vec3> points, double minSeparation, size_t& a, size_t& b) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t l, size_t r) { return points[l].x < points[r].x; });
  for (size_t i = 0; i < order.size(); ++i) {
    const glm::dvec3 pi(points[order[i]]);
    for (size_t j = i + 1; j < order.size(); ++j) {
      const glm::dvec3 pj(points[order[j]]);
      if (pj.x - pi.x >= minSeparation) break;
      if (glm::length(pj - pi) < minSeparation) {
        a = std::min(order[i], order[j]);
        b = std::max(order[i], order[j]);
        return true;
      }
    }
  }
  return false;
}

eng::Result<void> requireSize(size_t actual, size_t expected, const char* what) {
  if (actual != expected)
    return eng::makeError(eng::ErrorKind::InvalidArgument, std::string("RBF: ") + what + " has " + std::to_string(actual) + " entries, expected " +
                          std::to_string(expected));
  return {};
}

eng::Result<void> requireFinite(std::span<const glm::vec3> values, const char* what) {
  if (const long bad = firstNonFinite(values); bad >= 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, std::string("RBF: ") + what + " " + std::to_string(bad) + " of " +
                          std::to_string(values.size()) + " is not finite " + describe(values[static_cast<size_t>(bad)]));
  return {};
}

// The inputs build() accepts: enough finite, separated points, a kernel with
// valid parameters and one finite, non-negative smoothing weight per point.
eng::Result<void> validateBuildInputs(std::span<const glm::vec3> controlPoints, const RbfKernel& kernel, float minSeparation,
                                      std::span<const double> smoothing) {
  const size_t n = controlPoints.size();
  if (n < 4)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: " + std::to_string(n) +
                          " control points given, at least 4 are needed (the affine term has 4 unknowns)");
  if (const long bad = firstNonFinite(controlPoints); bad >= 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: control point " + std::to_string(bad) + " of " + std::to_string(n) +
                          " is not finite " + describe(controlPoints[static_cast<size_t>(bad)]));
  if (kernel.type == RbfKernelType::Polyharmonic && kernel.k < 1)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: polyharmonic kernel needs k >= 1 (exponent 2k+1), got k = " + std::to_string(kernel.k));
  if (kernel.type == RbfKernelType::Multiquadric && !(std::isfinite(kernel.c) && kernel.c > 0.0f))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: multiquadric kernel needs a finite shape parameter c > 0, got c = " +
                          std::to_string(kernel.c));
  if (!(std::isfinite(minSeparation) && minSeparation >= 0.0f))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: minSeparation must be finite and >= 0, got " + std::to_string(minSeparation));
  if (!smoothing.empty() && smoothing.size() != n)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: " + std::to_string(smoothing.size()) +
                          " smoothing weights given for " + std::to_string(n) + " control points");
  for (size_t i = 0; i < smoothing.size(); ++i)
    if (!(std::isfinite(smoothing[i]) && smoothing[i] >= 0.0))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: smoothing weight " + std::to_string(i) + " of " +
                            std::to_string(n) + " must be finite and >= 0, got " + std::to_string(smoothing[i]));
  if (size_t a = 0, b = 0; findCoincidentPair(controlPoints, minSeparation, a, b))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: control points " + std::to_string(a) + " and " + std::to_string(b) + " of " +
                          std::to_string(n) + " coincide " + describe(controlPoints[a]) + " (closer than minSeparation " +
                          std::to_string(minSeparation) + ")");
  return {};
}

// The affine part is solvable only when the points span 3D: checked on the
// singular values of the centred layout.
eng::Result<void> requireSpans3D(const std::vector<glm::dvec3>& points) {
  const size_t n = points.size();
  Eigen::MatrixX3d centred(static_cast<Eigen::Index>(n), 3);
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& p : points) mean += p;
  mean /= double(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 d = points[i] - mean;
    centred.row(static_cast<Eigen::Index>(i)) << d.x, d.y, d.z;
  }
  const Eigen::Vector3d spread = Eigen::JacobiSVD<Eigen::MatrixX3d>(centred).singularValues();
  if (spread(1) <= kMinRelativeSpread * spread(0))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: the " + std::to_string(n) +
                          " control points are collinear; the affine term needs a layout that spans 3D");
  if (spread(2) <= kMinRelativeSpread * spread(0))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: the " + std::to_string(n) +
                          " control points are coplanar; the affine term needs a layout that spans 3D");
  return {};
}

}  // namespace

double RbfKernel::operator()(double r) const {
  switch (type) {
    case RbfKernelType::Biharmonic:
      return r;
    case RbfKernelType::Polyharmonic: {
      double value = r;  // r^(2k+1) by repeated multiplication: exact for small k, no pow()
      const double r2 = r * r;
      for (int i = 0; i < k; ++i) value *= r2;
      return value;
    }
    case RbfKernelType::Multiquadric:
      return std::sqrt(r * r + double(c) * double(c));
  }
  return r;
}

eng::Result<RbfInterpolator> RbfInterpolator::build(std::span<const glm::vec3> controlPoints, const RbfKernel& kernel,
                                                     float minSeparation, std::span<const double> smoothing) {
  if (auto valid = validateBuildInputs(controlPoints, kernel, minSeparation, smoothing); !valid) return valid.error();
  const size_t n = controlPoints.size();

  RbfInterpolator rbf;
  rbf.kernel_ = kernel;

  // Normalise to a unit box: centre on the bounds, divide by the largest extent.
  glm::dvec3 lo(controlPoints[0]), hi(controlPoints[0]);
  for (const glm::vec3& p : controlPoints) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const glm::dvec3 extent = hi - lo;
  const double size = std::max({extent.x, extent.y, extent.z});
  rbf.centre_ = (lo + hi) * 0.5;
  rbf.invScale_ = size > 0.0 ? 1.0 / size : 1.0;
  rbf.normalisedKernel_ = kernel;
  rbf.normalisedKernel_.c = static_cast<float>(double(kernel.c) * rbf.invScale_);
  rbf.points_.reserve(n);
  for (const glm::vec3& p : controlPoints) rbf.points_.push_back(rbf.normalise(p));

  if (auto spans = requireSpans3D(rbf.points_); !spans) return spans.error();

  // [Phi P; P^T 0]: symmetric but indefinite, hence LU rather than Cholesky.
  const Eigen::Index N = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(N + 4, N + 4);
  for (Eigen::Index i = 0; i < N; ++i) {
    rbf.basisRow(rbf.points_[static_cast<size_t>(i)], system.row(i));
    system.block(N, i, 4, 1) = system.block(i, N, 1, 4).transpose();
  }
  // The energy a kernel measures is +phi for r^3 and -phi for r, r^5 and the
  // multiquadric (their conditional definiteness), so the misfit's weight
  // goes on the diagonal with that sign.
  const double energySign = kernel.type == RbfKernelType::Polyharmonic && kernel.k % 2 == 1 ? 1.0 : -1.0;
  for (size_t i = 0; i < smoothing.size(); ++i) {
    const Eigen::Index d = static_cast<Eigen::Index>(i);
    system(d, d) += energySign * smoothing[i];
  }
  rbf.inverseSystem_.compute(system);
  const double rcond = rbf.inverseSystem_.rcond();
  if (!(rcond > kMinReciprocalCondition))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF: the system for " + std::to_string(n) +
                          " control points is numerically singular (reciprocal condition " + std::to_string(rcond) +
                          "); spread the points out or use another kernel");
  return rbf;
}

void RbfInterpolator::basisRow(const glm::dvec3& x, RowRef row) const {
  const Eigen::Index n = static_cast<Eigen::Index>(points_.size());
  for (Eigen::Index j = 0; j < n; ++j) row(j) = normalisedKernel_(glm::length(x - points_[static_cast<size_t>(j)]));
  row(n) = 1.0;
  row(n + 1) = x.x;
  row(n + 2) = x.y;
  row(n + 3) = x.z;
}

eng::Result<Eigen::MatrixX3d> RbfInterpolator::solve(std::span<const glm::vec3> displacements) const {
  if (auto r = requireSize(displacements.size(), points_.size(), "displacement field"); !r) return r.error();
  if (auto r = requireFinite(displacements, "displacement"); !r) return r.error();
  const Eigen::Index n = static_cast<Eigen::Index>(points_.size());
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(n + 4, 3);  // side conditions: zero rows
  for (Eigen::Index i = 0; i < n; ++i) {
    const glm::vec3& d = displacements[static_cast<size_t>(i)];
    rhs.row(i) << d.x, d.y, d.z;
  }
  return Eigen::MatrixX3d(inverseSystem_.solve(rhs));
}

eng::Result<glm::vec3> RbfInterpolator::evaluate(const Eigen::MatrixX3d& coefficients, const glm::vec3& x) const {
  if (auto r = requireSize(static_cast<size_t>(coefficients.rows()), points_.size() + 4, "coefficient matrix"); !r)
    return r.error();
  if (auto r = requireFinite(std::span<const glm::vec3>(&x, 1), "evaluation point"); !r) return r.error();
  // The basis row times the coefficients, summed as it is made, over plain
  // arrays: no row to allocate, no Eigen or glm operator left out of line in
  // a sanitized build (an autorig transfer evaluates a warp six times per
  // vertex of the source face).
  const glm::dvec3 p = normalise(x);
  const size_t n = points_.size();
  const double* cx = coefficients.col(0).data();
  const double* cy = coefficients.col(1).data();
  const double* cz = coefficients.col(2).data();
  glm::dvec3 value(cx[n] + p.x * cx[n + 1] + p.y * cx[n + 2] + p.z * cx[n + 3],
                   cy[n] + p.x * cy[n + 1] + p.y * cy[n + 2] + p.z * cy[n + 3],
                   cz[n] + p.x * cz[n + 1] + p.y * cz[n + 2] + p.z * cz[n + 3]);
  const bool biharmonic = normalisedKernel_.type == RbfKernelType::Biharmonic;
  const glm::dvec3* points = points_.data();
  for (size_t j = 0; j < n; ++j) {
    const double dx = p.x - points[j].x, dy = p.y - points[j].y, dz = p.z - points[j].z;
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double phi = biharmonic ? r : normalisedKernel_(r);
    value.x += phi * cx[j];
    value.y += phi * cy[j];
    value.z += phi * cz[j];
  }
  return glm::vec3(value);
}

eng::Result<Eigen::MatrixXd> RbfInterpolator::influenceMatrix(std::span<const glm::vec3> points) const {
  if (auto r = requireFinite(points, "point"); !r) return r.error();
  const Eigen::Index n = static_cast<Eigen::Index>(points_.size());
  const Eigen::Index m = static_cast<Eigen::Index>(points.size());
  // Columns of the inverse system for unit displacements of each control point
  // (zero side-condition rows): A^-1 [I; 0].
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(n + 4, n);
  unit.topRows(n).setIdentity();
  const Eigen::MatrixXd coefficientsPerControl = inverseSystem_.solve(unit);
  Eigen::MatrixXd basis(m, n + 4);
  for (Eigen::Index v = 0; v < m; ++v) basisRow(normalise(points[static_cast<size_t>(v)]), basis.row(v));
  return Eigen::MatrixXd(basis * coefficientsPerControl);
}

eng::Result<RbfDeformer> RbfDeformer::build(std::span<const glm::vec3> controlPoints, std::span<const glm::vec3> points,
                                             const RbfKernel& kernel) {
  eng::Result<RbfInterpolator> interpolator = RbfInterpolator::build(controlPoints, kernel);
  if (!interpolator) return interpolator.error();
  return build(*interpolator, points);
}

eng::Result<RbfDeformer> RbfDeformer::build(const RbfInterpolator& interpolator, std::span<const glm::vec3> points) {
  if (const long bad = firstNonFinite(points); bad >= 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF deformer: point " + std::to_string(bad) + " of " + std::to_string(points.size()) +
                          " is not finite " + describe(points[static_cast<size_t>(bad)]));
  auto influence = interpolator.influenceMatrix(points);
  if (!influence) return influence.error();
  RbfDeformer deformer;
  deformer.influence_ = influence->cast<float>();
  return deformer;
}

eng::Result<void> RbfDeformer::apply(std::span<const glm::vec3> displacements, std::span<glm::vec3> out,
                                     FalloffMask mask) const {
  const size_t n = controlPointCount();
  const size_t m = pointCount();
  if (displacements.size() != n || out.size() != m || (!mask.empty() && mask.size() != m))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "RBF deformer: apply got " + std::to_string(displacements.size()) + " displacements, " +
                          std::to_string(out.size()) + " outputs, mask of " + std::to_string(mask.size()) +
                          "; expected " + std::to_string(n) + " displacements, " + std::to_string(m) +
                          " outputs, mask empty or " + std::to_string(m));
  // Displacements go structure-of-arrays in chunks on the stack, so each output
  // coordinate is a dot product of two contiguous float runs (vectorised) and
  // the influence matrix is still read exactly once.
  constexpr size_t kChunk = 256;
  alignas(32) float xs[kChunk], ys[kChunk], zs[kChunk];
  using Vec = Eigen::Map<const Eigen::VectorXf, Eigen::Aligned32>;
  for (glm::vec3& o : out) o = glm::vec3(0.0f);
  for (size_t first = 0; first < n; first += kChunk) {
    const size_t count = std::min(kChunk, n - first);
    for (size_t j = 0; j < count; ++j) {
      xs[j] = displacements[first + j].x;
      ys[j] = displacements[first + j].y;
      zs[j] = displacements[first + j].z;
    }
    const Eigen::Index len = static_cast<Eigen::Index>(count);
    const Vec x(xs, len), y(ys, len), z(zs, len);
    for (size_t v = 0; v < m; ++v) {
      const auto row = influence_.row(static_cast<Eigen::Index>(v)).segment(static_cast<Eigen::Index>(first), len);
      out[v] += glm::vec3(row.dot(x), row.dot(y), row.dot(z));
    }
  }
  if (!mask.empty())
    for (size_t v = 0; v < m; ++v) out[v] *= mask[v];
  return {};
}

}  // namespace facial
