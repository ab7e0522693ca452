#include "autorig/dense_correspondence.h"

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

// The landmarks the warp passes through rather than near: where the lips and the lids meet and end.
TEST(ClosingLines, NameTheLidsTheMouthCornersAndTheInnerLips) {
  std::vector<size_t> held;
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i)
    if (autorig::onClosingLine(i)) held.push_back(i);
  const std::vector<size_t> expected{36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47, 48, 54, 60, 61, 62, 63, 64, 65, 66, 67};
  EXPECT_EQ(held, expected);
}

}  // namespace
