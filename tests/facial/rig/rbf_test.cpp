// RbfInterpolator / RbfDeformer: interpolation, affine reproduction,
// convergence, falloff; then the layouts and calls that must be refused.
#include "facial/runtime/rbf.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace facial {
namespace {

const RbfKernel kKernels[] = {
    {RbfKernelType::Biharmonic, 1, 0.1f},
    {RbfKernelType::Polyharmonic, 1, 0.1f},
    {RbfKernelType::Polyharmonic, 2, 0.1f},
    {RbfKernelType::Multiquadric, 1, 0.3f},
};

std::string kernelName(const RbfKernel& k) {
  switch (k.type) {
    case RbfKernelType::Biharmonic: return "biharmonic";
    case RbfKernelType::Polyharmonic: return "polyharmonic k=" + std::to_string(k.k);
    case RbfKernelType::Multiquadric: return "multiquadric c=" + std::to_string(k.c);
  }
  return "?";
}

std::vector<glm::vec3> randomPoints(size_t count, float lo, float hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<glm::vec3> points(count);
  for (glm::vec3& p : points) p = glm::vec3(u(rng), u(rng), u(rng));
  return points;
}

std::vector<glm::vec3> grid(int perAxis) {
  std::vector<glm::vec3> points;
  for (int i = 0; i < perAxis; ++i)
    for (int j = 0; j < perAxis; ++j)
      for (int k = 0; k < perAxis; ++k)
        points.emplace_back(float(i) / float(perAxis - 1), float(j) / float(perAxis - 1), float(k) / float(perAxis - 1));
  return points;
}

glm::vec3 smoothField(const glm::vec3& p) {
  return glm::vec3(std::sin(2.0f * p.x) * std::cos(p.y), std::exp(-p.z) * p.x, 0.5f * p.x * p.y + std::cos(p.z));
}

TEST(RbfKernel, EvaluatesTheDocumentedFunctions) {
  EXPECT_DOUBLE_EQ((RbfKernel{RbfKernelType::Biharmonic, 1, 0.1f})(2.0), 2.0);
  EXPECT_DOUBLE_EQ((RbfKernel{RbfKernelType::Polyharmonic, 1, 0.1f})(2.0), 8.0);
  EXPECT_DOUBLE_EQ((RbfKernel{RbfKernelType::Polyharmonic, 2, 0.1f})(2.0), 32.0);
  EXPECT_NEAR((RbfKernel{RbfKernelType::Multiquadric, 1, 0.5f})(2.0), std::sqrt(4.25), 1e-12);
}

TEST(RbfInterpolator, ReproducesControlDisplacementsExactly) {
  const std::vector<glm::vec3> controls = randomPoints(40, -1.0f, 1.0f, 1);
  const std::vector<glm::vec3> displacements = randomPoints(40, -0.2f, 0.2f, 2);
  for (const RbfKernel& kernel : kKernels) {
    SCOPED_TRACE(kernelName(kernel));
    auto rbf = RbfInterpolator::build(controls, kernel);
    ASSERT_TRUE(rbf) << rbf.error().message;
    EXPECT_EQ(rbf->controlPointCount(), 40u);
    const Eigen::MatrixX3d coefficients = *rbf->solve(displacements);
    ASSERT_EQ(coefficients.rows(), 44);
    for (size_t i = 0; i < controls.size(); ++i) {
      const glm::vec3 value = *rbf->evaluate(coefficients, controls[i]);
      EXPECT_NEAR(value.x, displacements[i].x, 1e-5f) << "control " << i;
      EXPECT_NEAR(value.y, displacements[i].y, 1e-5f) << "control " << i;
      EXPECT_NEAR(value.z, displacements[i].z, 1e-5f) << "control " << i;
    }
  }
}

TEST(RbfInterpolator, ReproducesAffineFieldsFarFromControlsWithEveryKernel) {
  const std::vector<glm::vec3> controls = randomPoints(30, 0.0f, 1.0f, 3);
  const glm::mat3 linear(0.3f, -0.2f, 0.1f, 0.05f, 0.4f, -0.3f, -0.1f, 0.2f, 0.25f);
  const glm::vec3 offset(0.1f, -0.05f, 0.2f);
  auto affine = [&](const glm::vec3& p) { return linear * p + offset; };
  std::vector<glm::vec3> displacements;
  for (const glm::vec3& p : controls) displacements.push_back(affine(p));
  // Probes 3 to 6 layout sizes away from every control point.
  std::vector<glm::vec3> probes;
  for (const glm::vec3& dir : randomPoints(50, -1.0f, 1.0f, 4))
    probes.push_back(glm::vec3(0.5f) + glm::normalize(dir) * (3.0f + 3.0f * std::abs(dir.x)));

  for (const RbfKernel& kernel : kKernels) {
    SCOPED_TRACE(kernelName(kernel));
    auto rbf = RbfInterpolator::build(controls, kernel);
    ASSERT_TRUE(rbf) << rbf.error().message;
    const Eigen::MatrixX3d coefficients = *rbf->solve(displacements);
    // The radial weights vanish: the side conditions leave only the affine term.
    // (Not exactly zero: the float inputs carry ~1e-7 rounding, amplified by the
    // system's conditioning; without the side conditions they would be O(1).)
    EXPECT_LT(coefficients.topRows(30).cwiseAbs().maxCoeff(), 1e-3);
    for (const glm::vec3& p : probes) {
      const glm::vec3 expected = affine(p);
      const glm::vec3 value = *rbf->evaluate(coefficients, p);
      EXPECT_NEAR(glm::length(value - expected), 0.0f, 1e-4f * (1.0f + glm::length(expected)));
    }
  }
}

// A smoothing spline: with a weight on each point the interpolant passes
// near an outlier, between it and the field the others make, for every
// kernel (the weight goes on the system's diagonal with the sign of the
// kernel's energy; the wrong sign overshoots the outlier or blows up), and
// still reproduces an affine field exactly.
TEST(RbfInterpolator, SmoothingPassesNearAnOutlierAndKeepsAffineFields) {
  const std::vector<glm::vec3> controls = randomPoints(30, 0.0f, 1.0f, 9);
  const glm::mat3 linear(0.3f, -0.2f, 0.1f, 0.05f, 0.4f, -0.3f, -0.1f, 0.2f, 0.25f);
  auto affine = [&](const glm::vec3& p) { return linear * p + glm::vec3(0.1f, -0.05f, 0.2f); };
  std::vector<glm::vec3> field, spiked;
  for (const glm::vec3& p : controls) field.push_back(affine(p));
  spiked = field;
  constexpr size_t kOutlier = 7;
  const glm::vec3 spike(0.0f, 0.3f, 0.0f);
  spiked[kOutlier] += spike;
  for (const RbfKernel& kernel : kKernels) {
    SCOPED_TRACE(kernelName(kernel));
    const std::vector<double> none(controls.size(), 0.0), some(controls.size(), 0.05);
    auto exact = RbfInterpolator::build(controls, kernel, 1e-6f, none);
    auto smooth = RbfInterpolator::build(controls, kernel, 1e-6f, some);
    ASSERT_TRUE(exact && smooth);
    const glm::vec3 through = *exact->evaluate(*exact->solve(spiked), controls[kOutlier]);
    EXPECT_NEAR(glm::length(through - spiked[kOutlier]), 0.0f, 1e-5f) << "a weight of 0 is interpolation";
    const float share = glm::dot(*smooth->evaluate(*smooth->solve(spiked), controls[kOutlier]) - field[kOutlier], spike) /
                        glm::dot(spike, spike);
    EXPECT_GT(share, 0.02f) << "the outlier still pulls";
    EXPECT_LT(share, 0.98f) << "the outlier is not passed through";
    const Eigen::MatrixX3d affineOnly = *smooth->solve(field);
    for (const glm::vec3& p : randomPoints(20, -1.0f, 2.0f, 10))
      EXPECT_NEAR(glm::length(*smooth->evaluate(affineOnly, p) - affine(p)), 0.0f, 1e-4f);
  }
}

TEST(RbfInterpolator, ErrorFallsAsControlPointsAreAdded) {
  const std::vector<glm::vec3> probes = randomPoints(400, 0.05f, 0.95f, 5);
  for (const RbfKernel& kernel : kKernels) {
    SCOPED_TRACE(kernelName(kernel));
    std::vector<double> maxErrors;
    for (int perAxis : {2, 3, 4, 5}) {  // 8, 27, 64, 125 points
      const std::vector<glm::vec3> controls = grid(perAxis);
      std::vector<glm::vec3> values;
      for (const glm::vec3& p : controls) values.push_back(smoothField(p));
      auto rbf = RbfInterpolator::build(controls, kernel);
      ASSERT_TRUE(rbf) << rbf.error().message;
      const Eigen::MatrixX3d coefficients = *rbf->solve(values);
      double worst = 0.0;
      for (const glm::vec3& p : probes)
        worst = std::max(worst, double(glm::length(*rbf->evaluate(coefficients, p) - smoothField(p))));
      maxErrors.push_back(worst);
    }
    for (size_t i = 1; i < maxErrors.size(); ++i)
      EXPECT_LT(maxErrors[i], maxErrors[i - 1]) << "going from " << (i + 1) << "^3 to " << (i + 2) << "^3 points";
    // 125 points must beat 8 points clearly, not just by rounding.
    EXPECT_LT(maxErrors.back(), 0.25 * maxErrors.front());
  }
}

TEST(RbfInterpolator, InterpolantIsIndependentOfTheLayoutsScaleAndPosition) {
  const std::vector<glm::vec3> controls = randomPoints(20, -1.0f, 1.0f, 6);
  const std::vector<glm::vec3> displacements = randomPoints(20, -0.1f, 0.1f, 7);
  const float scale = 250.0f;
  const glm::vec3 shift(1000.0f, -40.0f, 7.0f);
  std::vector<glm::vec3> moved;
  for (const glm::vec3& p : controls) moved.push_back(p * scale + shift);
  const RbfKernel multiquadric{RbfKernelType::Multiquadric, 1, 0.2f};
  const RbfKernel movedMultiquadric{RbfKernelType::Multiquadric, 1, 0.2f * scale};
  for (auto [kernel, movedKernel] : {std::pair{kKernels[0], kKernels[0]}, std::pair{kKernels[1], kKernels[1]},
                                     std::pair{multiquadric, movedMultiquadric}}) {
    SCOPED_TRACE(kernelName(kernel));
    auto a = RbfInterpolator::build(controls, kernel);
    auto b = RbfInterpolator::build(moved, movedKernel);
    ASSERT_TRUE(a && b);
    const Eigen::MatrixX3d ca = *a->solve(displacements);
    const Eigen::MatrixX3d cb = *b->solve(displacements);
    for (const glm::vec3& p : randomPoints(20, -1.5f, 1.5f, 8))
      EXPECT_NEAR(glm::length(*a->evaluate(ca, p) - *b->evaluate(cb, p * scale + shift)), 0.0f, 1e-4f);
  }
}

TEST(RbfDeformer, MatchesTheInterpolatorAtFixedPoints) {
  const std::vector<glm::vec3> controls = randomPoints(25, -1.0f, 1.0f, 9);
  const std::vector<glm::vec3> points = randomPoints(300, -1.2f, 1.2f, 10);
  const std::vector<glm::vec3> displacements = randomPoints(25, -0.1f, 0.1f, 11);
  const RbfKernel kernel{RbfKernelType::Polyharmonic, 1, 0.1f};
  auto rbf = RbfInterpolator::build(controls, kernel);
  auto deformer = RbfDeformer::build(controls, points, kernel);
  ASSERT_TRUE(rbf && deformer);
  EXPECT_EQ(deformer->pointCount(), 300u);
  EXPECT_EQ(deformer->controlPointCount(), 25u);
  std::vector<glm::vec3> out(points.size());
  ASSERT_TRUE(deformer->apply(displacements, out));
  const Eigen::MatrixX3d coefficients = *rbf->solve(displacements);
  for (size_t v = 0; v < points.size(); ++v)
    EXPECT_NEAR(glm::length(out[v] - *rbf->evaluate(coefficients, points[v])), 0.0f, 1e-5f) << "point " << v;
}

TEST(RbfDeformer, ReproducesControlDisplacementsWhenBakedAtTheControls) {
  const std::vector<glm::vec3> controls = randomPoints(16, 0.0f, 1.0f, 12);
  const std::vector<glm::vec3> displacements = randomPoints(16, -0.3f, 0.3f, 13);
  auto deformer = RbfDeformer::build(controls, controls, RbfKernel{});
  ASSERT_TRUE(deformer);
  std::vector<glm::vec3> out(controls.size());
  ASSERT_TRUE(deformer->apply(displacements, out));
  for (size_t i = 0; i < controls.size(); ++i) EXPECT_NEAR(glm::length(out[i] - displacements[i]), 0.0f, 1e-5f);
  // Influence rows at the controls are the identity.
  EXPECT_NEAR(deformer->influence(3, 3), 1.0f, 1e-5f);
  EXPECT_NEAR(deformer->influence(3, 4), 0.0f, 1e-5f);
}

TEST(RbfDeformer, FalloffMaskScalesEachPoint) {
  const std::vector<glm::vec3> controls = randomPoints(12, 0.0f, 1.0f, 14);
  const std::vector<glm::vec3> points = randomPoints(3, 0.0f, 1.0f, 15);
  const std::vector<glm::vec3> displacements(12, glm::vec3(0.0f, 1.0f, 0.0f));  // rigid shift
  auto deformer = RbfDeformer::build(controls, points, RbfKernel{});
  ASSERT_TRUE(deformer);
  const std::vector<float> mask = {1.0f, 0.5f, 0.0f};
  std::vector<glm::vec3> out(3);
  ASSERT_TRUE(deformer->apply(displacements, out, mask));
  EXPECT_NEAR(out[0].y, 1.0f, 1e-5f);
  EXPECT_NEAR(out[1].y, 0.5f, 1e-5f);
  EXPECT_NEAR(out[2].y, 0.0f, 1e-6f);
}

// ---- refused layouts and calls ----

std::vector<glm::vec3> tetrahedron() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; }

TEST(RbfValidity, RejectsFewerThanFourPoints) {
  const std::vector<glm::vec3> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  auto rbf = RbfInterpolator::build(three, RbfKernel{});
  ASSERT_FALSE(rbf);
  EXPECT_NE(rbf.error().message.find("3 control points"), std::string::npos) << rbf.error().message;
  EXPECT_NE(rbf.error().message.find("at least 4"), std::string::npos) << rbf.error().message;
  EXPECT_FALSE(RbfInterpolator::build({}, RbfKernel{}));
}

TEST(RbfValidity, RejectsCoincidentPointsNamingBoth) {
  std::vector<glm::vec3> points = tetrahedron();
  points.push_back({1, 1, 1});
  points.push_back({1, 0, 0});  // same as point 1
  auto rbf = RbfInterpolator::build(points, RbfKernel{});
  ASSERT_FALSE(rbf);
  EXPECT_NE(rbf.error().message.find("control points 1 and 5"), std::string::npos) << rbf.error().message;
  EXPECT_NE(rbf.error().message.find("coincide"), std::string::npos) << rbf.error().message;
  // Closer than a caller-chosen separation counts too.
  points.back() = {1.0f, 0.001f, 0.0f};
  EXPECT_TRUE(RbfInterpolator::build(points, RbfKernel{}));
  EXPECT_FALSE(RbfInterpolator::build(points, RbfKernel{}, 0.01f));
}

TEST(RbfValidity, RejectsCoplanarAndCollinearLayouts) {
  const std::vector<glm::vec3> plane = {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1, 1, 2}, {0.5f, 0.3f, 2}};
  auto coplanar = RbfInterpolator::build(plane, RbfKernel{});
  ASSERT_FALSE(coplanar);
  EXPECT_NE(coplanar.error().message.find("coplanar"), std::string::npos) << coplanar.error().message;
  EXPECT_NE(coplanar.error().message.find("5 control points"), std::string::npos) << coplanar.error().message;

  const std::vector<glm::vec3> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  auto collinear = RbfInterpolator::build(line, RbfKernel{});
  ASSERT_FALSE(collinear);
  EXPECT_NE(collinear.error().message.find("collinear"), std::string::npos) << collinear.error().message;

  // A tilted plane is just as singular.
  std::vector<glm::vec3> tilted;
  for (const glm::vec3& p : randomPoints(20, 0.0f, 1.0f, 16)) tilted.push_back({p.x, p.y, 0.3f * p.x - 0.7f * p.y});
  EXPECT_FALSE(RbfInterpolator::build(tilted, RbfKernel{}));
}

TEST(RbfValidity, RejectsNonFiniteInputsNamingTheIndex) {
  std::vector<glm::vec3> points = tetrahedron();
  points.push_back({0.5f, std::numeric_limits<float>::quiet_NaN(), 0.5f});
  auto rbf = RbfInterpolator::build(points, RbfKernel{});
  ASSERT_FALSE(rbf);
  EXPECT_NE(rbf.error().message.find("control point 4 of 5"), std::string::npos) << rbf.error().message;

  points.back() = {0.5f, 0.5f, 0.5f};
  std::vector<glm::vec3> probes = {{0, 0, 0}, {std::numeric_limits<float>::infinity(), 0, 0}};
  auto deformer = RbfDeformer::build(points, probes, RbfKernel{});
  ASSERT_FALSE(deformer);
  EXPECT_NE(deformer.error().message.find("point 1 of 2"), std::string::npos) << deformer.error().message;

  auto ok = RbfInterpolator::build(points, RbfKernel{});
  ASSERT_TRUE(ok);
  std::vector<glm::vec3> displacements(5, glm::vec3(0.0f));
  displacements[2].z = std::numeric_limits<float>::quiet_NaN();
  auto refused = ok->solve(displacements);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("displacement 2 of 5 is not finite"), std::string::npos) << refused.error().message;
  auto nowhere = ok->evaluate(Eigen::MatrixX3d::Zero(9, 3), glm::vec3(0.0f, std::numeric_limits<float>::infinity(), 0.0f));
  ASSERT_FALSE(nowhere);
  EXPECT_NE(nowhere.error().message.find("evaluation point 0 of 1 is not finite"), std::string::npos)
      << nowhere.error().message;
}

TEST(RbfValidity, RejectsInvalidKernels) {
  auto poly = RbfInterpolator::build(tetrahedron(), RbfKernel{RbfKernelType::Polyharmonic, 0, 0.1f});
  ASSERT_FALSE(poly);
  EXPECT_NE(poly.error().message.find("k = 0"), std::string::npos) << poly.error().message;
  auto mq = RbfInterpolator::build(tetrahedron(), RbfKernel{RbfKernelType::Multiquadric, 1, 0.0f});
  ASSERT_FALSE(mq);
  EXPECT_NE(mq.error().message.find("c > 0"), std::string::npos) << mq.error().message;
}

TEST(RbfValidity, RejectsSmoothingWeightsThatDoNotFit) {
  const std::vector<double> three(3, 0.1);
  auto wrongCount = RbfInterpolator::build(tetrahedron(), RbfKernel{}, 1e-6f, three);
  ASSERT_FALSE(wrongCount);
  EXPECT_NE(wrongCount.error().message.find("3 smoothing weights given for 4 control points"), std::string::npos)
      << wrongCount.error().message;
  for (double bad : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::vector<double> weights{0.0, 0.0, bad, 0.0};
    auto refused = RbfInterpolator::build(tetrahedron(), RbfKernel{}, 1e-6f, weights);
    ASSERT_FALSE(refused) << bad;
    EXPECT_NE(refused.error().message.find("smoothing weight 2 of 4"), std::string::npos) << refused.error().message;
  }
}

TEST(RbfValidity, SizeMismatchesNameTheSizes) {
  auto rbf = RbfInterpolator::build(tetrahedron(), RbfKernel{});
  ASSERT_TRUE(rbf);
  const std::vector<glm::vec3> five(5);
  auto solved = rbf->solve(five);
  ASSERT_FALSE(solved) << "solve accepted 5 displacements for 4 controls";
  EXPECT_NE(solved.error().message.find("5 entries, expected 4"), std::string::npos) << solved.error().message;
  auto evaluated = rbf->evaluate(Eigen::MatrixX3d::Zero(7, 3), glm::vec3(0.0f));
  ASSERT_FALSE(evaluated);
  EXPECT_NE(evaluated.error().message.find("coefficient matrix has 7 entries, expected 8"), std::string::npos)
      << evaluated.error().message;

  auto deformer = RbfDeformer::build(tetrahedron(), five, RbfKernel{});
  ASSERT_TRUE(deformer);
  std::vector<glm::vec3> out(5);
  auto wrongControls = deformer->apply(five, out);
  ASSERT_FALSE(wrongControls);
  EXPECT_NE(wrongControls.error().message.find("5 displacements"), std::string::npos) << wrongControls.error().message;
  EXPECT_NE(wrongControls.error().message.find("expected 4 displacements"), std::string::npos);
  const std::vector<glm::vec3> four(4);
  std::vector<glm::vec3> shortOut(3);
  EXPECT_FALSE(deformer->apply(four, shortOut));
  const std::vector<float> badMask(2, 1.0f);
  EXPECT_FALSE(deformer->apply(four, out, badMask));
  EXPECT_TRUE(deformer->apply(four, out));
}

}  // namespace
}  // namespace facial
