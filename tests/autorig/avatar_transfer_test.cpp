// A Ready Player Me avatar with visemes only (../shared/speech/rpm-visemes.glb:
// skinned, with hair, glasses, body and outfit) gets the head's units and the
// ARKit shapes; its visemes stay, its hair and clothes do not move.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "autorig/face_parts.h"
#include "autorig/mouth_opening.h"
#include "autorig/surface_cast.h"
#include "autorig/target_transfer.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "tests/autorig/transfer_fixture.h"
#include "tests/common/test_support.h"

namespace {

TEST(AvatarTransfer, RiggsAVisemesOnlyAvatar) {
  FACIAL_REQUIRE_SHARED();
  eng::Result<eng::Model> avatar = eng::loadModel(testing_support::sharedDir() / "speech/rpm-visemes.glb");
  ASSERT_TRUE(avatar) << avatar.error().message;
  const autorig::PosedFace posed = autorig::poseAtRest(*avatar);
  autorig::FaceLandmarks landmarks;
  const std::optional<autorig::TransferResult> rigged =
      transfer_fixture::rigWithFixtureLandmarks(*avatar, posed, "rpm-visemes.landmarks.json", &landmarks,
                                                transfer_fixture::kShapesOnly);
  ASSERT_TRUE(rigged);
  const auto& made = rigged->report.made;
  for (const char* name : {"AU12_LipCornerPuller_L", "mouthSmileLeft", "eyeBlinkLeft", "jawOpen", "browInnerUp"})
    EXPECT_NE(std::find(made.begin(), made.end(), name), made.end()) << name;
  for (const std::string& warning : rigged->report.warnings) std::printf("warning: %s\n", warning.c_str());
  // Meshes other than the head, teeth, eyes (and whatever the parts call skin) get nothing.
  for (size_t m = 0; m < avatar->meshes.size(); ++m) {
    const eng::Mesh& before = avatar->meshes[m];
    const eng::Mesh& after = rigged->model.meshes[m];
    std::printf("%s: %zu -> %zu targets\n", before.name.c_str(), before.targetNames.size(), after.targetNames.size());
    // Every target the mesh had is still there, first and in order.
    ASSERT_GE(after.targetNames.size(), before.targetNames.size());
    EXPECT_TRUE(std::equal(before.targetNames.begin(), before.targetNames.end(), after.targetNames.begin()));
    if (before.name.find("Hair") != std::string::npos || before.name.find("Glasses") != std::string::npos ||
        before.name.find("Outfit") != std::string::npos) {
      EXPECT_EQ(after.targetNames.size(), before.targetNames.size()) << before.name;
    }
  }
  // A blink closes every column of the eye: the inner third too, where the
  // share of the lid's turn carried from the head fell short (0.27 of the
  // gap stayed open between 43 and 47, 0.23 between 38 and 40) until each
  // column was closed on its own.
  size_t head = 0;
  while (head < avatar->meshes.size() && avatar->meshes[head].name != "Wolf3D_Head") ++head;
  ASSERT_LT(head, avatar->meshes.size());
  const std::array<std::array<size_t, 2>, 4> columns{{{37, 41}, {38, 40}, {43, 47}, {44, 46}}};
  for (const auto& [upper, lower] : columns) {
    const float gap = transfer_fixture::lidGap(rigged->model, head, posed, landmarks, upper < 42 ? "eyeBlinkRight" : "eyeBlinkLeft",
                                               std::array<size_t, 1>{upper}, std::array<size_t, 1>{lower});
    std::printf("lid gap %zu-%zu at a blink: %.2f of the gap at rest\n", upper, lower, gap);
    EXPECT_LT(gap, 0.1f) << upper << "-" << lower;
  }
  const auto out = testing_support::freshTempDir("avatar_transfer") / "rpm-visemes-rigged.glb";
  eng::Result<void> saved = eng::saveModel(rigged->model, out);
  EXPECT_TRUE(saved) << saved.error().message;
}

}  // namespace

// The same avatar without its teeth mesh (many avatars come without): the
// built-in head's mouth, teeth and tongue are carried in, skinned as its
// head is, and the rigged file saves and loads with them.
TEST(AvatarTransfer, AnAvatarWithoutTeethGetsTheHeads) {
  FACIAL_REQUIRE_SHARED();
  eng::Result<eng::Model> avatar = eng::loadModel(testing_support::sharedDir() / "speech/rpm-visemes.glb");
  ASSERT_TRUE(avatar) << avatar.error().message;
  for (eng::Node& node : avatar->nodes)
    if (node.name == "Wolf3D_Teeth") node.mesh = -1, node.skin = -1;
  const autorig::PosedFace posed = autorig::poseAtRest(*avatar);
  const std::optional<eng::Model> builtIn = transfer_fixture::loadHead();
  ASSERT_TRUE(builtIn);
  const autorig::SourceFace source = transfer_fixture::headSource(*builtIn);
  eng::Result<autorig::FaceLandmarks> read =
      autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/rpm-visemes.landmarks.json");
  ASSERT_TRUE(read) << read.error().message;
  const autorig::FaceLandmarks& landmarks = *read;
  eng::Model face = *avatar;
  const autorig::FaceParts parts = autorig::findFaceParts(face, posed, landmarks);
  const autorig::MouthOpening opening = autorig::openTheMouth(face, posed, landmarks, parts, source);
  EXPECT_EQ(opening.cutVertices, 0u);
  ASSERT_GT(opening.insideVertices, 0u);
  size_t head = 0;
  while (head < face.meshes.size() && face.meshes[head].name != "Wolf3D_Head") ++head;
  ASSERT_LT(head, face.meshes.size());
  const eng::Mesh& mesh = face.meshes[head];
  const size_t sets = mesh.primitives[0].influenceSets();
  ASSERT_GT(sets, 0u) << "the avatar's head is skinned";
  for (size_t i = 1; i < mesh.primitives.size(); ++i) {
    EXPECT_EQ(mesh.primitives[i].influenceSets(), sets) << "carried piece " << i << " is skinned as the head";
    EXPECT_EQ(mesh.primitives[i].targets.size(), mesh.targetNames.size());
  }
  // Posed as drawn, the carried teeth sit between the avatar's eyes and chin, behind its lips.
  const autorig::PosedFace after = autorig::poseAtRest(face);
  const autorig::LandmarkFrame frame(landmarks);
  // The lips' front: the outer lips' middles (51 above, 57 below).
  const float lipsFront = std::max(glm::dot(landmarks.points[51], frame.forward()), glm::dot(landmarks.points[57], frame.forward()));
  for (const autorig::PosedPrimitive& pp : after.primitives) {
    if (pp.mesh != head || pp.primitive == 0) continue;
    for (const glm::vec3& q : pp.positions) {
      EXPECT_LT(std::abs(frame.sideOf(q)), 0.6f);
      EXPECT_LT(frame.aboveLipLine(q), 0.35f);
      EXPECT_LT(glm::dot(q, frame.forward()), lipsFront);
    }
  }
  const auto out = testing_support::freshTempDir("avatar_transfer") / "rpm-without-teeth-opened.glb";
  eng::Result<void> saved = eng::saveModel(face, out);
  ASSERT_TRUE(saved) << saved.error().message;
  eng::Result<eng::Model> loaded = eng::loadModel(out);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->meshes[head].primitives.size(), mesh.primitives.size());
}

// The same avatar as Ready Player Me exports it with a texture atlas: every
// opaque mesh merged into one primitive, the see-through glasses into a
// second, no names but the avatar's. Its parts are told by shape as the
// meshes' names tell them: its lenses once passed as a pair of eyeballs (the
// lids turned about points in front of the face) and took the eyes'
// landmarks onto them.
TEST(AvatarTransfer, AnAvatarMergedByATextureAtlasHasItsPartsByShape) {
  FACIAL_REQUIRE_SHARED();
  eng::Result<eng::Model> avatar = eng::loadModel(testing_support::sharedDir() / "speech/rpm-visemes.glb");
  ASSERT_TRUE(avatar) << avatar.error().message;
  eng::Result<autorig::FaceLandmarks> landmarks =
      autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/rpm-visemes.landmarks.json");
  ASSERT_TRUE(landmarks) << landmarks.error().message;
  const autorig::PosedFace posed = autorig::poseAtRest(*avatar);
  const autorig::FaceParts asMeshes = autorig::findFaceParts(*avatar, posed, *landmarks);
  // Drawn as it stands, in world space: one opaque primitive, one see-through.
  eng::Model merged;
  merged.meshes.push_back({});
  merged.meshes[0].name = "Wolf3D_Avatar";
  merged.meshes[0].primitives.resize(2);
  for (const char* name : {"Wolf3D_Avatar", "Wolf3D_Avatar_Transparent"}) {
    eng::Material material;
    material.name = name;
    merged.materials.push_back(material);
  }
  merged.materials[1].alphaMode = eng::AlphaMode::Blend;
  size_t teeth = 0;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const autorig::PosedPrimitive& pp = posed.primitives[i];
    const eng::Primitive& from = avatar->meshes[pp.mesh].primitives[pp.primitive];
    const bool seeThrough = from.material >= 0 && avatar->materials[size_t(from.material)].alphaMode == eng::AlphaMode::Blend;
    eng::Primitive& to = merged.meshes[0].primitives[seeThrough ? 1 : 0];
    to.material = seeThrough ? 1 : 0;
    const uint32_t first = uint32_t(to.positions.size());
    to.positions.insert(to.positions.end(), pp.positions.begin(), pp.positions.end());
    for (uint32_t index : from.indices) to.indices.push_back(first + index);
    for (autorig::FacePart part : asMeshes.vertexParts[i])
      teeth += part == autorig::FacePart::UpperTeeth || part == autorig::FacePart::LowerTeeth || part == autorig::FacePart::Tongue;
  }
  for (eng::Primitive& p : merged.meshes[0].primitives) p.normals.assign(p.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  eng::Node node;
  node.name = "Wolf3D_Avatar";
  node.mesh = 0;
  merged.nodes.push_back(node);
  merged.roots.push_back(0);
  const autorig::PosedFace mergedPosed = autorig::poseAtRest(merged);
  ASSERT_EQ(mergedPosed.primitives.size(), 2u);
  const autorig::FaceParts parts = autorig::findFaceParts(merged, mergedPosed, *landmarks);
  for (const std::string& note : parts.notes) std::printf("%s\n", note.c_str());
  const auto count = [](const std::vector<autorig::FacePart>& of, std::initializer_list<autorig::FacePart> which) {
    return size_t(std::count_if(of.begin(), of.end(), [&](autorig::FacePart p) { return std::find(which.begin(), which.end(), p) != which.end(); }));
  };
  EXPECT_EQ(count(parts.vertexParts[1], {autorig::FacePart::Glasses}), parts.vertexParts[1].size());
  using P = autorig::FacePart;
  EXPECT_EQ(count(parts.vertexParts[0], {P::UpperTeeth, P::LowerTeeth, P::Tongue}), teeth);
  ASSERT_TRUE(parts.eyeballsFound && asMeshes.eyeballsFound);
  const float span = autorig::LandmarkFrame(*landmarks).eyeSpan();
  for (size_t e = 0; e < 2; ++e) {
    EXPECT_LT(glm::distance(parts.eyeCentres[e], asMeshes.eyeCentres[e]), 0.02f * span) << e;
    EXPECT_NEAR(parts.eyeRadii[e], asMeshes.eyeRadii[e], 0.02f * span) << e;
  }
  // The landmarks are cast onto the opaque primitive only.
  const std::vector<bool> outer = autorig::outerSkinPrimitives(merged, mergedPosed);
  EXPECT_TRUE(outer[0]);
  EXPECT_FALSE(outer[1]);
}
