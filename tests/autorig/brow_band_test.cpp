// A face's painted brows (autorig/brow_band.h): found on an avatar whose
// brows are dark on its skin, not found without a texture or on a forehead
// as dark as the brows; raised, they keep their width instead of
// stretching into bars (the units that raise them, on Ready Player Me's
// heavy, low brows: ../shared/speech/rpm-visemes.glb).
#include <algorithm>
#include <array>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "autorig/brow_band.h"
#include "autorig/dense_correspondence.h"
#include "autorig/face_frame.h"
#include "autorig/face_parts.h"
#include "autorig/target_transfer.h"
#include "engine/scene/gltf_loader.h"
#include "tests/autorig/transfer_fixture.h"
#include "tests/common/test_support.h"

namespace {

struct Avatar {
  eng::Model model;
  autorig::PosedFace posed;
  autorig::FaceLandmarks landmarks;
};

std::optional<Avatar> loadAvatar() {
  eng::Result<eng::Model> model = eng::loadModel(testing_support::sharedDir() / "speech/rpm-visemes.glb");
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return std::nullopt;
  }
  eng::Result<autorig::FaceLandmarks> landmarks =
      autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/rpm-visemes.landmarks.json");
  if (!landmarks) {
    ADD_FAILURE() << landmarks.error().message;
    return std::nullopt;
  }
  autorig::PosedFace posed = autorig::poseAtRest(*model);
  return Avatar{std::move(*model), std::move(posed), *landmarks};
}

// The brows as the transfer looks for them: on the skin, lashes and brows it moves.
autorig::BrowBand browsOf(const Avatar& avatar, autorig::FaceSurface* surfaceOut = nullptr) {
  const autorig::FaceParts parts = autorig::findFaceParts(avatar.model, avatar.posed, avatar.landmarks);
  autorig::FaceSurface surface = autorig::gatherSurface(avatar.model, avatar.posed, parts,
                                                        {autorig::FacePart::Skin, autorig::FacePart::Lashes,
                                                         autorig::FacePart::Brows});
  autorig::BrowBand band = autorig::findBrows(avatar.model, avatar.posed, surface, avatar.landmarks);
  if (surfaceOut) *surfaceOut = std::move(surface);
  return band;
}

TEST(BrowBand, AnAvatarsPaintedBrowsAreFound) {
  FACIAL_REQUIRE_SHARED();
  const std::optional<Avatar> avatar = loadAvatar();
  ASSERT_TRUE(avatar);
  const autorig::BrowBand band = browsOf(*avatar);
  for (size_t b = 0; b < 2; ++b) {
    std::printf("brow %zu: %zu vertices, down to %.2f eye spans under the brow line\n", b,
                band.brows[b].covered.size(), double(band.brows[b].reach));
    // Its brows cover 0.1-0.24 eye spans over the lid, the points lying on their upper edge.
    EXPECT_GT(band.brows[b].reach, 0.05f) << b;
    EXPECT_LT(band.brows[b].reach, 0.2f) << b;
    EXPECT_GE(band.brows[b].covered.size(), 10u) << b;
  }
}

TEST(BrowBand, NoneAreFoundWithoutATextureOrOnAForeheadAsDark) {
  FACIAL_REQUIRE_SHARED();
  std::optional<Avatar> avatar = loadAvatar();
  ASSERT_TRUE(avatar);
  std::vector<eng::Material> painted = avatar->model.materials;
  for (eng::Material& m : avatar->model.materials) m.baseColorImage = -1;
  EXPECT_FALSE(browsOf(*avatar).found()) << "one colour everywhere";
  // The skin painted the brows' colour all over: a fringe, a dark forehead.
  avatar->model.materials = painted;
  for (eng::Image& image : avatar->model.images)
    for (size_t i = 0; i + 3 < image.rgba8.size(); i += 4) image.rgba8[i] = 40, image.rgba8[i + 1] = 30, image.rgba8[i + 2] = 25;
  EXPECT_FALSE(browsOf(*avatar).found()) << "as dark as the brows";
}

// How much each brow triangle grows in the face's plane with the brow
// raisers at 1 (AU1 + both AU2: surprise's brows), over its area at rest:
// the median over the triangles the brows cover. 1: they rise whole.
float browStretch(const Avatar& avatar, const eng::Model& rigged) {
  autorig::FaceSurface surface;
  const autorig::BrowBand band = browsOf(avatar, &surface);
  const glm::vec3 up = autorig::LandmarkFrame(avatar.landmarks).up();
  std::vector<glm::vec3> moved = surface.positions;
  for (size_t v = 0; v < surface.positions.size(); ++v) {
    const autorig::PosedPrimitive& pp = avatar.posed.primitives[surface.vertices[v].primitive];
    const eng::Mesh& mesh = rigged.meshes[pp.mesh];
    for (const char* unit : {"AU1_InnerBrowRaiser", "AU2_OuterBrowRaiser_L", "AU2_OuterBrowRaiser_R"}) {
      const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), unit);
      if (it == mesh.targetNames.end()) continue;
      const glm::vec3 local = mesh.primitives[pp.primitive].targets[size_t(it - mesh.targetNames.begin())]
                                  .positions[surface.vertices[v].vertex];
      moved[v] += glm::inverse(pp.worldToLocal[surface.vertices[v].vertex]) * local;
    }
  }
  const glm::vec3 side = autorig::LandmarkFrame(avatar.landmarks).side();
  std::vector<float> stretch;
  for (const std::array<uint32_t, 3>& t : surface.triangles) {
    if (std::any_of(t.begin(), t.end(), [&](uint32_t v) { return band.coverage[v] < 0.5f; })) continue;
    // Its area in the face's plane: a brow bending (the inner end rising
    // more) keeps it, one stretching across grows it.
    auto area = [&](const std::vector<glm::vec3>& p) {
      const glm::vec3 a = p[t[1]] - p[t[0]], b = p[t[2]] - p[t[0]];
      return 0.5f * std::abs(glm::dot(a, side) * glm::dot(b, up) - glm::dot(a, up) * glm::dot(b, side));
    };
    if (area(surface.positions) > 0.0f) stretch.push_back(area(moved) / area(surface.positions));
  }
  if (stretch.empty()) return 0.0f;
  std::nth_element(stretch.begin(), stretch.begin() + std::ptrdiff_t(stretch.size() / 2), stretch.end());
  std::printf("%zu brow triangles, median stretch %.2f\n", stretch.size(), double(stretch[stretch.size() / 2]));
  return stretch[stretch.size() / 2];
}

TEST(BrowBand, RaisedBrowsKeepTheirWidth) {
  FACIAL_REQUIRE_SHARED();
  const std::optional<Avatar> avatar = loadAvatar();
  ASSERT_TRUE(avatar);
  const std::optional<autorig::TransferResult> rigged = transfer_fixture::rigWithFixtureLandmarks(
      avatar->model, avatar->posed, "rpm-visemes.landmarks.json", nullptr, transfer_fixture::kShapesOnly);
  ASSERT_TRUE(rigged);
  const auto& notes = rigged->report.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& n) { return n.starts_with("brows found"); }));
  // Carried point by point, the brows' triangles grew to 1.41 times their
  // area (the lower rows rising half as far as the upper); now 1.11.
  EXPECT_LT(browStretch(*avatar, rigged->model), 1.2f);
}

}  // namespace
