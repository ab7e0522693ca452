#include "autorig/dense_correspondence.h"

#include <cstdio>

#include <gtest/gtest.h>

#include "autorig/closest_point.h"
#include "autorig/face_parts.h"
#include "autorig/posed_face.h"
#include "tests/common/test_meshes.h"

namespace {

// Two triangles side by side: the second's corner at (1, 0, 0) is a copy of
// the first's with other texture coordinates (a UV seam: one point of the
// surface), its corner at (0, 1, 0) a copy with the same ones (a slit the
// author made, as between a closed mouth's lips). Labelled and moved, the
// seam's copies are one vertex; the slit's stay two.
TEST(FaceSurface, UvSeamCopiesAreOnePointAndSlitCopiesStayApart) {
  eng::Primitive prim;
  prim.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  prim.normals.assign(prim.positions.size(), glm::vec3(0, 0, 1));
  prim.texcoords = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0.5f}, {0, 1}, {1, 1}};
  prim.indices = {0, 1, 2, 3, 5, 4};
  const eng::Model model = testing_support::singleMeshModel(eng::Mesh{.name = "skin", .primitives = {prim}});
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  autorig::FaceParts parts;
  parts.vertexParts = {std::vector<autorig::FacePart>(prim.positions.size(), autorig::FacePart::Skin)};
  const autorig::FaceSurface surface = autorig::gatherSurface(model, posed, parts, {autorig::FacePart::Skin});
  ASSERT_EQ(surface.positions.size(), 6u);
  EXPECT_EQ(surface.rootOf(3), 1u);  // the seam's copy
  EXPECT_EQ(surface.rootOf(4), 4u);  // the slit's copy
  for (size_t v : {0u, 1u, 2u, 5u}) EXPECT_EQ(surface.rootOf(v), v);

  // Without texture coordinates nothing tells a seam from a slit: no copies are joined.
  eng::Primitive bare = prim;
  bare.texcoords.clear();
  const eng::Model untextured = testing_support::singleMeshModel(eng::Mesh{.name = "skin", .primitives = {bare}});
  const autorig::FaceSurface plain =
      autorig::gatherSurface(untextured, autorig::poseAtRest(untextured), parts, {autorig::FacePart::Skin});
  for (size_t v = 0; v < plain.positions.size(); ++v) EXPECT_EQ(plain.rootOf(v), v);
}

// A triangle reaching across the lips' meeting line (a mouth corner: one
// corner on the upper lip, two on the lower) is neither lip's to match: upper
// lip skin there took the lower lip's motion and tore when the lip rose. One
// across an eye's corner stays both lids'. A query from outside any region
// refuses nothing.
TEST(TriangleGrid, ATriangleAcrossTheLipsIsNeitherLipsAndOneAcrossTheLidsIsBoth) {
  using autorig::FaceRegion;
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::array<uint32_t, 3>> triangles = {{0, 1, 2}};
  const glm::vec3 onIt(0.2f, 0.2f, 0.0f);
  auto found = [&](std::vector<FaceRegion> corners, FaceRegion refused) {
    const autorig::TriangleGrid grid(positions, triangles, corners);
    return grid.closest(onIt, refused, 1.0f).found;
  };
  const std::vector<FaceRegion> lips = {FaceRegion::UpperLip, FaceRegion::LowerLip, FaceRegion::LowerLip};
  EXPECT_FALSE(found(lips, FaceRegion::LowerLip));  // an upper lip vertex's query
  EXPECT_FALSE(found(lips, FaceRegion::UpperLip));  // a lower lip vertex's
  EXPECT_TRUE(found(lips, FaceRegion::None));
  const std::vector<FaceRegion> lids = {FaceRegion::LeftUpperLid, FaceRegion::LeftLowerLid, FaceRegion::None};
  EXPECT_TRUE(found(lids, FaceRegion::LeftLowerLid));
  EXPECT_TRUE(found(lids, FaceRegion::LeftUpperLid));
  const std::vector<FaceRegion> lowerLid = {FaceRegion::LeftLowerLid, FaceRegion::LeftLowerLid, FaceRegion::None};
  EXPECT_FALSE(found(lowerLid, FaceRegion::LeftLowerLid));
  const std::vector<FaceRegion> upperLip = {FaceRegion::UpperLip, FaceRegion::None, FaceRegion::None};
  EXPECT_TRUE(found(upperLip, FaceRegion::LowerLip));
  EXPECT_FALSE(found(upperLip, FaceRegion::UpperLip));
}

}  // namespace

namespace {

// The landmarks the warp passes through rather than near: the lids' lines
// and the mouth's corners (the inner lips' middles it passes near).
TEST(ClosingLines, NameTheLidsAndTheMouthCorners) {
  std::vector<size_t> lids, corners;
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    if (autorig::onLidLine(i)) lids.push_back(i);
    if (autorig::atMouthCorner(i)) corners.push_back(i);
  }
  EXPECT_EQ(lids, (std::vector<size_t>{36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47}));
  EXPECT_EQ(corners, (std::vector<size_t>{48, 54, 60, 64}));
}

// A face in the z = 0 plane with the landmarks a frame needs: eye corners
// 36/39 and 42/45, the chin 8, and the mouth's corners.
autorig::FaceLandmarks flatFace(float scale, const glm::vec2& rightOuter, const glm::vec2& rightInner,
                                const glm::vec2& leftInner, const glm::vec2& leftOuter) {
  autorig::FaceLandmarks l;
  for (size_t i = 0; i < l.points.size(); ++i) l.points[i] = scale * glm::vec3(0.01f * float(i), 0.5f, 0.1f);
  l.points[36] = scale * glm::vec3(-3, 2, 0), l.points[39] = scale * glm::vec3(-1, 2, 0);
  l.points[42] = scale * glm::vec3(1, 2, 0), l.points[45] = scale * glm::vec3(3, 2, 0);
  l.points[8] = scale * glm::vec3(0, -6, 0);
  l.points[48] = glm::vec3(rightOuter, 0.3f), l.points[60] = glm::vec3(rightInner, 0.2f);
  l.points[64] = glm::vec3(leftInner, 0.2f), l.points[54] = glm::vec3(leftOuter, 0.3f);
  return l;
}

// dlib's outer and inner mouth corners, found a little off on a face twice
// the source's size (the inner right one outside its outer one): each pair
// keeps its middle and is spaced as the source's, twice as wide, give or take
// 0.02 of the mouth's width; nothing else moves, nor any point out of the
// face's plane. Pairs spaced within that of the source's stay as found.
TEST(SteadyMouthCorners, KeepEachCornersMiddleAndNearlyTheSourcesSpacing) {
  const autorig::FaceLandmarks source = flatFace(1.0f, {-2.0f, -3.0f}, {-1.6f, -3.1f}, {1.6f, -3.1f}, {2.0f, -3.0f});
  const autorig::FaceLandmarks found = flatFace(2.0f, {-4.0f, -6.0f}, {-4.5f, -6.4f}, {3.0f, -6.3f}, {4.0f, -6.1f});
  const autorig::FaceLandmarks steady = autorig::withSteadyMouthCorners(source, found);
  const float width = glm::length(glm::vec2(found.points[54] - found.points[48]));
  auto expectPair = [&](size_t outer, size_t inner, const glm::vec2& sourceSpacing) {
    const glm::vec2 middle = 0.5f * glm::vec2(found.points[outer] + found.points[inner]);
    EXPECT_NEAR(glm::length(0.5f * glm::vec2(steady.points[outer] + steady.points[inner]) - middle), 0.0f, 1e-5f) << outer;
    const glm::vec2 spacing = glm::vec2(steady.points[inner] - steady.points[outer]);
    EXPECT_NEAR(glm::distance(spacing, 0.25f * width * sourceSpacing), 0.02f * width, 1e-4f) << inner;
    EXPECT_EQ(steady.points[outer].z, found.points[outer].z);
    EXPECT_EQ(steady.points[inner].z, found.points[inner].z);
  };
  expectPair(48, 60, {0.4f, -0.1f});
  expectPair(54, 64, {-0.4f, -0.1f});
  for (size_t i = 0; i < found.points.size(); ++i) {
    if (autorig::atMouthCorner(i)) continue;
    EXPECT_EQ(steady.points[i], found.points[i]) << i;
  }
  const autorig::FaceLandmarks near = flatFace(2.0f, {-4.0f, -6.0f}, {-3.25f, -6.15f}, {3.2f, -6.2f}, {4.0f, -6.0f});
  const autorig::FaceLandmarks kept = autorig::withSteadyMouthCorners(source, near);
  for (size_t i : {48, 54, 60, 64}) EXPECT_NEAR(glm::distance(kept.points[i], near.points[i]), 0.0f, 1e-5f) << i;
}

// The lips' line is the parabola nearest the mouth's corners and the inner
// lips' midpoints: one inner point found 0.3 above its place (as dlib's are
// on a face it does not know) moves the line there by less than half of
// that, where the line through the points moved by all of it; with the
// points on a parabola, the line is that parabola.
TEST(LipLine, IsTheParabolaNearestItsPoints) {
  auto lipsOn = [](float lift) {
    autorig::FaceLandmarks l = flatFace(1.0f, {-2.0f, -3.0f}, {-1.6f, -3.0f}, {1.6f, -3.0f}, {2.0f, -3.0f});
    auto at = [](float x) { return -3.0f - 0.25f * (1.0f - x * x / 4.0f); };  // 0 at the corners, -0.25 in the middle
    const std::array<std::array<size_t, 2>, 3> pairs{{{61, 67}, {62, 66}, {63, 65}}};
    const std::array<float, 3> xs{-0.8f, 0.0f, 0.8f};
    for (size_t k = 0; k < 3; ++k) {
      l.points[pairs[k][0]] = glm::vec3(xs[k], at(xs[k]) + 0.1f, 0.2f);
      l.points[pairs[k][1]] = glm::vec3(xs[k], at(xs[k]) - 0.1f, 0.2f);
    }
    l.points[48].y = l.points[60].y = l.points[64].y = l.points[54].y = at(2.0f);
    l.points[60].y = at(1.6f), l.points[64].y = at(1.6f);
    l.points[65].y += lift;
    return std::pair(l, at(0.8f));
  };
  const auto [clean, onLine] = lipsOn(0.0f);
  const autorig::LandmarkFrame exact(clean);
  EXPECT_NEAR(exact.aboveLipLine({0.8f, onLine, 0.2f}) * exact.eyeSpan(), 0.0f, 1e-3f);
  EXPECT_NEAR(exact.aboveLipLine({0.0f, -3.25f, 0.2f}) * exact.eyeSpan(), 0.0f, 1e-3f);
  const auto [lifted, unused] = lipsOn(0.6f);  // the pair's midpoint 0.3 up
  const autorig::LandmarkFrame off(lifted);
  const float moved = -off.aboveLipLine({0.8f, onLine, 0.2f}) * off.eyeSpan();
  std::printf("one midpoint 0.3 off moves the lips' line %.3f there\n", double(moved));
  EXPECT_GT(moved, 0.0f);
  EXPECT_LT(moved, 0.15f);
}

}  // namespace
