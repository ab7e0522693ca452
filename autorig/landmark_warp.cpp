#include "autorig/landmark_warp.h"

#include <cmath>
#include <string>
#include <vector>

namespace autorig {
namespace {

// Below this share of the largest singular value a point set counts as flat
// along that direction (a line or a point).
constexpr double kMinSpreadShare = 1e-4;

}  // namespace

eng::Result<Similarity> fitSimilarity(std::span<const glm::vec3> source, std::span<const glm::vec3> target) {
  if (source.size() != target.size() || source.size() < 3)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "similarity fit: " + std::to_string(source.size()) +
                                                               " source and " + std::to_string(target.size()) +
                                                               " target points (need the same count, at least 3)");
  const size_t n = source.size();
  Eigen::Vector3d meanS = Eigen::Vector3d::Zero(), meanT = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    meanS += Eigen::Vector3d(source[i].x, source[i].y, source[i].z);
    meanT += Eigen::Vector3d(target[i].x, target[i].y, target[i].z);
  }
  meanS /= double(n);
  meanT /= double(n);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double varianceS = 0.0, varianceT = 0.0;
  for (size_t i = 0; i < n; ++i) {
    Eigen::Vector3d s = Eigen::Vector3d(source[i].x, source[i].y, source[i].z) - meanS;
    Eigen::Vector3d t = Eigen::Vector3d(target[i].x, target[i].y, target[i].z) - meanT;
    covariance += t * s.transpose();
    varianceS += s.squaredNorm();
    varianceT += t.squaredNorm();
  }
  covariance /= double(n);
  varianceS /= double(n);
  varianceT /= double(n);
  if (!(varianceS > 0.0) || !(varianceT > 0.0) || !std::isfinite(varianceS + varianceT))
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "similarity fit: the " + std::string(varianceS > 0.0 ? "target" : "source") + "'s " +
                              std::to_string(n) + " points are collapsed to one point (or not finite)");
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (sigma(1) < kMinSpreadShare * sigma(0))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "similarity fit: the " + std::to_string(n) +
                                                               " point pairs lie on a line (no rotation is defined)");
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) mirror(2, 2) = -1.0;
  // A flat set (all landmarks nearly in one plane) has a free third axis: the
  // mirror is only meaningful when the smallest singular value carries weight.
  if (mirror(2, 2) < 0.0 && sigma(2) > 0.05 * sigma(1))
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "similarity fit: the target's " + std::to_string(n) +
                              " points are the source's mirrored (left and right swapped)");
  const Eigen::Matrix3d rotation = svd.matrixU() * mirror * svd.matrixV().transpose();
  const double scale = (sigma(0) + sigma(1) + mirror(2, 2) * sigma(2)) / varianceS;
  const Eigen::Vector3d translation = meanT - scale * rotation * meanS;
  Similarity result;
  result.scale = float(scale);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) result.rotation[c][r] = float(rotation(r, c));
  result.translation = glm::vec3(float(translation.x()), float(translation.y()), float(translation.z()));
  return result;
}

eng::Result<LandmarkWarp> LandmarkWarp::build(std::span<const glm::vec3> source, std::span<const glm::vec3> target,
                                              float minSeparation, std::span<const double> smoothing) {
  Similarity similarity = ENG_TRY_VALUE(fitSimilarity(source, target));
  std::vector<glm::vec3> moved(source.size()), residual(source.size());
  double sum = 0.0;
  for (size_t i = 0; i < source.size(); ++i) {
    moved[i] = similarity.apply(source[i]);
    residual[i] = target[i] - moved[i];
    sum += double(glm::dot(residual[i], residual[i]));
  }
  facial::RbfInterpolator rbf = ENG_TRY_VALUE(
      facial::RbfInterpolator::build(moved, facial::RbfKernel{.type = facial::RbfKernelType::Biharmonic},
                                     minSeparation * similarity.scale, smoothing));
  Eigen::MatrixX3d coefficients = ENG_TRY_VALUE(rbf.solve(residual));
  return LandmarkWarp(similarity, std::move(rbf), std::move(coefficients), float(std::sqrt(sum / double(source.size()))));
}

glm::vec3 LandmarkWarp::apply(const glm::vec3& p) const {
  const glm::vec3 moved = similarity_.apply(p);
  eng::Result<glm::vec3> bend = rbf_.evaluate(coefficients_, moved);
  // Only a non-finite p fails; it stays non-finite rather than silently moving.
  return bend ? moved + *bend : moved + glm::vec3(NAN);
}

glm::mat3 LandmarkWarp::jacobian(const glm::vec3& p, float step) const {
  glm::mat3 j(0.0f);
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 offset(0.0f);
    offset[axis] = step;
    j[axis] = (apply(p + offset) - apply(p - offset)) / (2.0f * step);
  }
  return j;
}

}  // namespace autorig
