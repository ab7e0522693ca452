// Casting picture pixels back onto the surface: rays hit the near side,
// whichever way the triangles wind, and the primitives rays stop at are the
// outer skin.
#include "autorig/surface_cast.h"

#include <algorithm>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "tests/common/test_meshes.h"

namespace {

// A camera 4 units in front (+Z) of the origin, looking at it; Vulkan clip
// space (y down) as the renderer's.
autorig::PictureCamera frontCamera() {
  glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(30.0f), 1.0f, 0.1f, 10.0f);
  projection[1][1] *= -1.0f;
  const glm::mat4 view = glm::lookAtRH(glm::vec3(0, 0, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  return {projection * view, glm::vec2(400.0f)};
}

const eng::Model& sphere() {
  static const eng::Model model = testing_support::makeSphereModel({.rings = 32, .segments = 48, .targets = 0});
  return model;
}

TEST(SurfaceCaster, HitsTheNearSideWhicheverWayTrianglesWind) {
  for (bool flipped : {false, true}) {
    eng::Model model = sphere();
    if (flipped)
      for (size_t t = 0; t + 2 < model.meshes[0].primitives[0].indices.size(); t += 3)
        std::swap(model.meshes[0].primitives[0].indices[t + 1], model.meshes[0].primitives[0].indices[t + 2]);
    const autorig::PosedFace posed = autorig::poseAtRest(model);
    const autorig::SurfaceCaster caster(model, posed, {true}, frontCamera());
    const auto centre = caster.cast({200.0f, 200.0f}, 4.0f);
    ASSERT_TRUE(centre);
    EXPECT_TRUE(centre->hit);
    EXPECT_NEAR(centre->position.z, 1.0f, 0.01f) << (flipped ? "flipped" : "as made");
    // Every vertex on the near side comes back where it is.
    const std::vector<glm::vec3>& vertices = posed.primitives[0].positions;
    for (size_t v = 0; v < vertices.size(); v += 7) {
      if (vertices[v].z < 0.3f) continue;
      const auto pixel = caster.project(vertices[v]);
      ASSERT_TRUE(pixel);
      const auto back = caster.cast(*pixel, 4.0f);
      ASSERT_TRUE(back);
      EXPECT_LT(glm::distance(back->position, vertices[v]), 1e-3f) << "vertex " << v;
    }
  }
}

TEST(SurfaceCaster, BesideTheOutlineTakesTheNearestVertexWithinReach) {
  const autorig::PosedFace posed = autorig::poseAtRest(sphere());
  const autorig::SurfaceCaster caster(sphere(), posed, {true}, frontCamera());
  // The outline seen from 4 units away: where the ray from the eye touches the sphere.
  const glm::vec2 rim = *caster.project({std::sqrt(15.0f) / 4.0f, 0.0f, 0.25f});
  const auto near = caster.cast(rim + glm::vec2(3.0f, 0.0f), 6.0f);
  ASSERT_TRUE(near);
  EXPECT_FALSE(near->hit);
  EXPECT_GT(near->position.x, 0.9f);
  EXPECT_FALSE(caster.cast(rim + glm::vec2(30.0f, 0.0f), 6.0f));
  EXPECT_FALSE(caster.cast({-5.0f, 200.0f}, 6.0f));  // off the picture
}

// A hit deeper than the limit is the inside of an opening (a mouth's back
// wall between parted lips): the nearest vertex no deeper than the limit,
// the rim, is taken instead.
TEST(SurfaceCaster, AHitTooDeepTakesTheRimInFrontOfIt) {
  const autorig::PosedFace posed = autorig::poseAtRest(sphere());
  const autorig::SurfaceCaster caster(sphere(), posed, {true}, frontCamera());
  EXPECT_NEAR(caster.depth({0.0f, 0.0f, 0.0f}) - caster.depth({0.0f, 0.0f, 1.0f}), 1.0f, 1e-4f);
  const glm::vec3 onSphere = glm::normalize(glm::vec3(0.6f, 0.13f, 0.8f));  // off the mesh's edges
  const glm::vec2 pixel = *caster.project(onSphere);
  const auto deep = caster.cast(pixel, 80.0f);
  ASSERT_TRUE(deep);
  EXPECT_TRUE(deep->hit);
  EXPECT_LT(glm::distance(deep->position, onSphere), 0.02f);
  const float limit = caster.depth({0.0f, 0.0f, 0.9f});
  const auto rim = caster.cast(pixel, 80.0f, limit);
  ASSERT_TRUE(rim);
  EXPECT_FALSE(rim->hit);
  EXPECT_LE(caster.depth(rim->position), limit);
  EXPECT_GT(rim->position.x, 0.3f);  // the rim beside the pixel, not the sphere's front
  EXPECT_FALSE(caster.cast(pixel, 2.0f, limit));  // no vertex that shallow within reach
}

TEST(SurfaceCaster, DistanceToTheSurface) {
  const autorig::PosedFace posed = autorig::poseAtRest(sphere());
  EXPECT_NEAR(autorig::distanceToSurface(sphere(), posed, {0.0f, 0.0f, 2.0f}), 1.0f, 0.01f);
  EXPECT_NEAR(autorig::distanceToSurface(sphere(), posed, {0.0f, 0.0f, 0.0f}), 1.0f, 0.01f);
  EXPECT_EQ(autorig::distanceToSurface(sphere(), posed, {0.0f, 0.0f, 2.0f}, {false}), INFINITY);
}

// The plaster head's eyes and teeth are named, a ball inside the head is
// not: rays stop only at the head.
TEST(SurfaceCaster, OuterSkinLeavesOutNamedAndEnclosedParts) {
  eng::Model model = testing_support::plasterHead();
  testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), "",
                                 {0.0f, 0.0f, 0.0f}, glm::vec3(0.3f));
  model.meshes.back().name.clear();
  for (eng::Material& m : model.materials) m.name.clear();
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  EXPECT_EQ(autorig::outerSkinPrimitives(model, posed), (std::vector<bool>{true, false, false, false, false}));
}

// A piece of the skin with a material of its own whose box lies inside the
// rest's (the lips: the nose stands out further) is skin the camera sees,
// and rays stop at it; a ball inside the head stays passed through.
TEST(SurfaceCaster, AnEnclosedPieceOfSkinTheCameraSeesIsSkin) {
  eng::Model model = testing_support::makeSphereModel({.rings = 32, .segments = 48, .targets = 0});
  model.meshes[0].name.clear();
  for (eng::Material& m : model.materials) m.name.clear();
  // The triangles about (0, -0.5, 0.87) as a primitive of their own.
  eng::Primitive& whole = model.meshes[0].primitives[0];
  eng::Primitive patch = whole;
  std::vector<uint32_t> rest;
  patch.indices.clear();
  for (size_t t = 0; t + 2 < whole.indices.size(); t += 3) {
    const glm::vec3 centre = (whole.positions[whole.indices[t]] + whole.positions[whole.indices[t + 1]] +
                              whole.positions[whole.indices[t + 2]]) / 3.0f;
    std::vector<uint32_t>& to = glm::distance(centre, glm::vec3(0.0f, -0.5f, 0.87f)) < 0.3f ? patch.indices : rest;
    to.insert(to.end(), whole.indices.begin() + ptrdiff_t(t), whole.indices.begin() + ptrdiff_t(t + 3));
  }
  ASSERT_FALSE(patch.indices.empty());
  whole.indices = rest;
  // The patch keeps only its own vertices (its box is theirs).
  std::vector<uint32_t> renumbered(patch.vertexCount(), UINT32_MAX);
  std::vector<glm::vec3> positions, normals;
  for (uint32_t& i : patch.indices) {
    if (renumbered[i] == UINT32_MAX) {
      renumbered[i] = uint32_t(positions.size());
      positions.push_back(patch.positions[i]), normals.push_back(patch.normals[i]);
    }
    i = renumbered[i];
  }
  patch.positions = positions, patch.normals = normals;
  patch.texcoords.clear(), patch.tangents.clear(), patch.colors.clear(), patch.targets.clear();
  model.meshes[0].primitives.push_back(patch);
  testing_support::addPartAsRoot(model, testing_support::makeSphereModel(testing_support::whiteSphereSpec(0)), "",
                                 {0.0f, 0.0f, 0.0f}, glm::vec3(0.3f));
  model.meshes.back().name.clear();
  for (eng::Material& m : model.materials) m.name.clear();
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  ASSERT_EQ(posed.primitives.size(), 3u);
  EXPECT_EQ(autorig::outerSkinPrimitives(model, posed), (std::vector<bool>{true, false, false})) << "both lie inside the sphere's box";
  EXPECT_EQ(autorig::seenSkinPrimitives(model, posed, frontCamera()), (std::vector<bool>{true, true, false}));
}

}  // namespace
