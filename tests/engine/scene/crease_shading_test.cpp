// Crease darkening baked per morph target (engine/scene/crease_shading.h):
// a target that folds or bunches the skin darkens where it does, one that
// only moves the surface does not.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "engine/scene/crease_shading.h"
#include "tests/common/test_meshes.h"

namespace {

constexpr int kSide = 11;  // vertices per side of the test sheet

eng::Primitive sheet() { return testing_support::flatSheet(kSide); }

size_t centre() { return size_t((kSide / 2) * kSide + kSide / 2); }

eng::MorphTarget targetFrom(const eng::Primitive& p, glm::vec3 (*delta)(glm::vec3)) {
  eng::MorphTarget t;
  for (const glm::vec3& q : p.positions) t.positions.push_back(delta(q));
  return t;
}

using Darkening = std::vector<std::vector<float>>;

float at(const Darkening& d, const eng::Primitive& p, size_t target, size_t vertex) {
  EXPECT_LT(target, d.size());
  if (d[target].empty()) return 0.0f;  // the target darkens nothing
  EXPECT_EQ(d[target].size(), p.positions.size());
  return d[target][vertex];
}

bool allZero(const Darkening& d) {
  return std::all_of(d.begin(), d.end(), [](const std::vector<float>& t) {
    return std::all_of(t.begin(), t.end(), [](float v) { return v == 0.0f; });
  });
}

TEST(CreaseShading, AFurrowDarkensAlongItsValleyOnly) {
  eng::Primitive p = sheet();
  // A groove along x = 0 sinking into the surface (a brow furrow).
  p.targets.push_back(targetFrom(p, [](glm::vec3 q) { return glm::vec3(0, 0, -0.08f * std::exp(-q.x * q.x / 0.004f)); }));
  const Darkening d = eng::bakeCreaseDarkening(p);
  ASSERT_EQ(d.size(), 1u);
  ASSERT_EQ(d[0].size(), p.positions.size());
  EXPECT_GT(at(d, p, 0, centre()), 0.3f) << "the valley floor";
  EXPECT_EQ(at(d, p, 0, size_t((kSide / 2) * kSide + 1)), 0.0f) << "flat skin far from the groove";
  EXPECT_TRUE(eng::hasCreases(d));
}

TEST(CreaseShading, BunchedSkinDarkensAndStretchedSkinDoesNot) {
  eng::Primitive p = sheet();
  p.targets.push_back(targetFrom(p, [](glm::vec3 q) { return glm::vec3(-0.4f * q.x, 0, 0); }));  // squeezed in x
  p.targets.push_back(targetFrom(p, [](glm::vec3 q) { return glm::vec3(0.4f * q.x, 0, 0); }));   // stretched
  const Darkening d = eng::bakeCreaseDarkening(p);
  EXPECT_GT(at(d, p, 0, centre()), 0.2f);
  EXPECT_EQ(at(d, p, 1, centre()), 0.0f);
}

TEST(CreaseShading, MovingOrBulgingTheSurfaceDoesNotDarkenIt) {
  eng::Primitive p = sheet();
  p.targets.push_back(targetFrom(p, [](glm::vec3) { return glm::vec3(0.1f, -0.2f, 0.3f); }));  // translation
  p.targets.push_back(targetFrom(p, [](glm::vec3 q) {  // a bump rising out of the surface
    return glm::vec3(0, 0, 0.05f * std::exp(-(q.x * q.x + q.y * q.y) / 0.02f));
  }));
  const Darkening d = eng::bakeCreaseDarkening(p);
  EXPECT_EQ(at(d, p, 0, centre()), 0.0f);
  EXPECT_EQ(at(d, p, 1, centre()), 0.0f) << "the top of a bump is convex";
  EXPECT_FALSE(eng::hasCreases(Darkening(d.begin(), d.begin() + 1)));
}

TEST(CreaseShading, SplitSeamVerticesGetTheSameValue) {
  eng::Primitive p = sheet();
  // Split the centre vertex: a copy at the same position owns half its triangles.
  const uint32_t copy = uint32_t(p.positions.size());
  p.positions.push_back(p.positions[centre()]);
  p.normals.push_back({0, 0, 1});
  for (size_t i = 0; i < p.indices.size() / 2; ++i)
    if (p.indices[i] == centre()) p.indices[i] = copy;
  p.targets.push_back(targetFrom(p, [](glm::vec3 q) { return glm::vec3(0, 0, -0.08f * std::exp(-q.x * q.x / 0.004f)); }));
  const Darkening d = eng::bakeCreaseDarkening(p);
  EXPECT_FLOAT_EQ(at(d, p, 0, copy), at(d, p, 0, centre()));
  EXPECT_GT(at(d, p, 0, copy), 0.3f);
}

TEST(CreaseShadingValidity, NothingToBakeGivesNoData) {
  eng::Primitive p = sheet();
  EXPECT_TRUE(eng::bakeCreaseDarkening(p).empty()) << "no targets";
  p.targets.push_back(targetFrom(p, [](glm::vec3) { return glm::vec3(0, 0, -1); }));
  eng::Primitive pointsOnly = p;
  pointsOnly.indices.clear();
  EXPECT_TRUE(eng::bakeCreaseDarkening(pointsOnly).empty()) << "no triangles";
}

TEST(CreaseShadingValidity, MalformedTargetsAndIndicesAreSkippedNotRead) {
  eng::Primitive p = sheet();
  eng::MorphTarget shortTarget;
  shortTarget.positions.resize(3, glm::vec3(0, 0, -1));
  p.targets.push_back(shortTarget);
  p.indices.insert(p.indices.end(), {0, 1, 99999});  // out of range: ignored
  const Darkening d = eng::bakeCreaseDarkening(p);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(d[0].empty()) << "a short target darkens nothing";
}

TEST(CreaseShadingValidity, NonFiniteDeltasDarkenNothing) {
  eng::Primitive p = sheet();
  p.targets.push_back(targetFrom(p, [](glm::vec3) { return glm::vec3(NAN, 0, 0); }));
  const Darkening d = eng::bakeCreaseDarkening(p);
  EXPECT_TRUE(allZero(d));
}

}  // namespace
