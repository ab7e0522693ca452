#include "autorig/eye_opening.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "autorig/skin_in_front.h"
#include "engine/scene/weights.h"
#include "tests/autorig/transfer_fixture.h"

namespace {

using transfer_fixture::headSource;
using transfer_fixture::loadHead;
using transfer_fixture::stripped;

// The built-in head as a scan whose eyes are its skin: no targets, its
// eyeballs dropped, and the skin seen through each opening (the socket's
// lining behind where the ball was) moved onto the ball's front: one surface
// with the lids, as a scan's eye is.
eng::Model eyesInTheSkin(const eng::Model& head, const autorig::SourceFace& source) {
  eng::Model face = stripped(head);
  for (eng::Node& node : face.nodes)
    if (node.name == "EyeLeft" || node.name == "EyeRight") node.mesh = -1;
  const autorig::PosedFace posed = autorig::poseAtRest(face);
  for (const autorig::PosedPrimitive& pp : posed.primitives) {
    if (face.meshes[pp.mesh].name != "Head" || pp.primitive != 0) continue;
    eng::Primitive& skin = face.meshes[pp.mesh].primitives[pp.primitive];
    for (size_t e = 0; e < 2; ++e) {
      const glm::vec3 c = source.parts.eyeCentres[e];
      const float r = source.parts.eyeRadii[e];
      for (size_t v = 0; v < pp.positions.size(); ++v) {
        const glm::vec3 d = pp.positions[v] - c;
        const float across = std::hypot(d.x, d.y);
        if (across >= 0.98f * r) continue;
        const float front = std::sqrt(r * r - across * across);
        if (d.z >= front || d.z <= -r) continue;
        skin.positions[v] += pp.toLocal(v, glm::vec3(0.0f, 0.0f, front - d.z));
      }
    }
  }
  return face;
}

// That face with the built-in head as its source, posed and its parts found.
struct ScanFace {
  std::unique_ptr<eng::Model> head;  // the source points into it
  autorig::SourceFace source;
  eng::Model face;
  autorig::PosedFace posed;
  autorig::FaceParts parts;

  // openTheEyes, then the face posed and its parts found again.
  autorig::EyeOpening open() {
    autorig::EyeOpening opening = autorig::openTheEyes(face, posed, source.landmarks, parts, source);
    posed = autorig::poseAtRest(face);
    parts = autorig::findFaceParts(face, posed, source.landmarks);
    return opening;
  }
};

std::optional<ScanFace> scanFace() {
  std::optional<eng::Model> head = loadHead();
  if (!head) return std::nullopt;
  ScanFace scan;
  scan.head = std::make_unique<eng::Model>(std::move(*head));
  scan.source = headSource(*scan.head);
  scan.face = eyesInTheSkin(*scan.head, scan.source);
  scan.posed = autorig::poseAtRest(scan.face);
  scan.parts = autorig::findFaceParts(scan.face, scan.posed, scan.source.landmarks);
  return scan;
}

size_t primitiveCount(const eng::Model& model) {
  size_t n = 0;
  for (const eng::Mesh& mesh : model.meshes) n += mesh.primitives.size();
  return n;
}

size_t countOf(const autorig::FaceParts& parts, autorig::FacePart part) {
  size_t n = 0;
  for (const std::vector<autorig::FacePart>& primitive : parts.vertexParts) n += size_t(std::count(primitive.begin(), primitive.end(), part));
  return n;
}

// A head exported without its eyeballs: each opening shows the inside of the
// skin (the sockets' lining). The head's eyeballs are set in them, at the
// balls the parts finder estimates behind the lids; found again, the face has
// eyeballs of its own there, and a second pass leaves it as it is.
TEST(EyeOpening, EmptyEyeOpeningsGetTheHeadsEyeballs) {
  const std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  eng::Model face = stripped(*head);
  for (eng::Node& node : face.nodes)
    if (node.name == "EyeLeft" || node.name == "EyeRight") node.mesh = -1;
  autorig::PosedFace posed = autorig::poseAtRest(face);
  autorig::FaceParts parts = autorig::findFaceParts(face, posed, source.landmarks);
  ASSERT_FALSE(parts.eyeballsFound);
  ASSERT_FALSE(parts.eyesInTheSkin[0] || parts.eyesInTheSkin[1]) << "open holes, not eyes in the skin";
  const size_t primitives = primitiveCount(face);

  const autorig::EyeOpening opening = autorig::openTheEyes(face, posed, source.landmarks, parts, source);
  EXPECT_EQ(opening.eyesFilled, 2u);
  EXPECT_EQ(opening.eyesCut, 0u);
  EXPECT_GT(opening.ballVertices, 1000u);
  EXPECT_EQ(primitiveCount(face), primitives + 2);
  ASSERT_EQ(opening.notes.size(), 2u);
  EXPECT_NE(opening.notes[0].find("nothing behind the right eye's opening"), std::string::npos) << opening.notes[0];

  posed = autorig::poseAtRest(face);
  parts = autorig::findFaceParts(face, posed, source.landmarks);
  EXPECT_TRUE(parts.eyeballsFound);
  for (size_t e = 0; e < 2; ++e) {
    SCOPED_TRACE(e);
    EXPECT_LT(glm::distance(parts.eyeCentres[e], source.parts.eyeCentres[e]), 0.35f * source.parts.eyeRadii[e])
        << "about where the head's own eyeball was";
    EXPECT_NEAR(parts.eyeRadii[e], source.parts.eyeRadii[e], 0.25f * source.parts.eyeRadii[e]);
  }
  EXPECT_FALSE(autorig::openTheEyes(face, posed, source.landmarks, parts, source).changed());
}

// A face with eyeballs of its own is left as it is.
TEST(EyeOpeningValidity, AFaceWithEyeballsIsLeftAsItIs) {
  const std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  eng::Model face = stripped(*head);
  const autorig::PosedFace posed = autorig::poseAtRest(face);
  const autorig::FaceParts parts = autorig::findFaceParts(face, posed, source.landmarks);
  const size_t primitives = primitiveCount(face);
  const autorig::EyeOpening opening = autorig::openTheEyes(face, posed, source.landmarks, parts, source);
  EXPECT_FALSE(opening.changed());
  EXPECT_EQ(primitiveCount(face), primitives);
}

// A scan's eyes in its skin are cut free from the lids, set back a little,
// and the head's eyeballs put behind them: found again, the face has two
// eyeballs by name (no eye in its skin) where the balls were, and the skin no
// longer holds them.
TEST(EyeOpening, AScansEyesAreCutFreeWithTheHeadsEyeballsBehind) {
  std::optional<ScanFace> scan = scanFace();
  ASSERT_TRUE(scan);
  const autorig::FaceParts before = scan->parts;
  ASSERT_TRUE(before.eyesInTheSkin[0] && before.eyesInTheSkin[1]) << "the fixture's eyes are its skin";
  const size_t onTheBalls = countOf(before, autorig::FacePart::EyeballRight) + countOf(before, autorig::FacePart::EyeballLeft);
  const size_t primitives = primitiveCount(scan->face);

  const autorig::EyeOpening opening = scan->open();
  EXPECT_EQ(opening.eyesCut, 2u);
  EXPECT_GT(opening.ballVertices, 1000u);
  EXPECT_EQ(primitiveCount(scan->face), primitives + 4) << "two cut-free eyes, two eyeballs behind them";
  ASSERT_EQ(opening.notes.size(), 2u);
  EXPECT_NE(opening.notes[0].find("cut free from its lids"), std::string::npos) << opening.notes[0];

  const eng::Model& face = scan->face;
  const autorig::PosedFace& posed = scan->posed;
  const autorig::FaceParts& after = scan->parts;
  EXPECT_TRUE(after.eyeballsFound);
  for (size_t e = 0; e < 2; ++e) {
    SCOPED_TRACE(e);
    EXPECT_FALSE(after.eyesInTheSkin[e]);
    EXPECT_LT(glm::distance(after.eyeCentres[e], before.eyeCentres[e]), 0.1f * before.eyeRadii[e]);
    EXPECT_NEAR(after.eyeRadii[e], before.eyeRadii[e], 0.05f * before.eyeRadii[e]);
  }
  // The skin's triangles on the balls moved to the eyes' own primitives, on
  // the balls (the fitted ball's centre lies about a millimetre from the
  // fixture's: within a tenth of the radius).
  size_t cutFree = 0;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const autorig::PosedPrimitive& pp = posed.primitives[i];
    const eng::Primitive& prim = face.meshes[pp.mesh].primitives[pp.primitive];
    if (prim.material < 0 || face.materials[size_t(prim.material)].name.find("a scan's") == std::string::npos) continue;
    const size_t e = after.vertexParts[i].front() == autorig::FacePart::EyeballRight ? 0 : 1;
    for (const glm::vec3& p : pp.positions) {
      EXPECT_NEAR(glm::distance(p, before.eyeCentres[e]), before.eyeRadii[e], 0.1f * before.eyeRadii[e]);
      ++cutFree;
    }
    EXPECT_TRUE(std::all_of(after.vertexParts[i].begin(), after.vertexParts[i].end(),
                            [&](autorig::FacePart p) { return p == after.vertexParts[i].front(); }));
  }
  // The white a raised lid uncovers is the scan's: the fixture's eye keeps
  // the skin's texels (the socket's lining, moved), so the head's white
  // eyeballs behind it are tinted towards skin.
  size_t balls = 0;
  for (const eng::Mesh& mesh : face.meshes)
    for (const eng::Primitive& prim : mesh.primitives)
      if (mesh.name == "Head" && prim.material >= 0 && face.materials[size_t(prim.material)].name == "Eye") {
        const glm::vec4 tint = face.materials[size_t(prim.material)].baseColorFactor;
        EXPECT_LT(tint.b, 0.95f);
        EXPECT_GT(tint.r, tint.b) << "towards the skin's colour";
        ++balls;
      }
  EXPECT_EQ(balls, 2u);
  EXPECT_GE(cutFree, onTheBalls * 9 / 10) << "the eyes' vertices, less those only at their rims";
  EXPECT_LE(cutFree, onTheBalls);

  // What is cut free is what shows at rest: no triangle of it lies under the
  // lids (a ray out of the face from its middle meets no skin).
  const autorig::LandmarkFrame frame(scan->source.landmarks);
  autorig::SkinInFront skin(frame, 0.1f * before.eyeRadii[0]);
  for (size_t i = 0; i < posed.primitives.size(); ++i)
    if (std::find(after.vertexParts[i].begin(), after.vertexParts[i].end(), autorig::FacePart::Skin) != after.vertexParts[i].end()) {
      const eng::Primitive& prim = face.meshes[posed.primitives[i].mesh].primitives[posed.primitives[i].primitive];
      for (size_t t = 0; t + 2 < prim.indices.size(); t += 3)
        skin.add(posed.primitives[i].positions[prim.indices[t]], posed.primitives[i].positions[prim.indices[t + 1]],
                 posed.primitives[i].positions[prim.indices[t + 2]]);
    }
  size_t underTheLids = 0;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const eng::Primitive& prim = face.meshes[posed.primitives[i].mesh].primitives[posed.primitives[i].primitive];
    if (prim.material < 0 || face.materials[size_t(prim.material)].name.find("a scan's") == std::string::npos) continue;
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      const auto& at = posed.primitives[i].positions;
      const glm::vec3 middle = (at[prim.indices[t]] + at[prim.indices[t + 1]] + at[prim.indices[t + 2]]) / 3.0f;
      underTheLids += skin.covers(middle + frame.forward() * (0.02f * before.eyeRadii[0]));
    }
  }
  EXPECT_EQ(underTheLids, 0u);
}

// Rigged, such a face's eyes turn for a gaze and its lids open over them:
// AU5 raises the upper lid and leaves the cut-free eye where it is, and the
// gaze shapes (not made for eyes in the skin) are made.
TEST(EyeOpening, TheCutFreeEyesTurnAndTheLidsOpenOverThem) {
  std::optional<ScanFace> scan = scanFace();
  ASSERT_TRUE(scan);
  ASSERT_TRUE(scan->open().changed());
  auto rigged = autorig::transferTargets(scan->source, scan->face, scan->posed, scan->source.landmarks, scan->parts,
                                             transfer_fixture::kShapesOnly);
  ASSERT_TRUE(rigged) << rigged.error().message;
  const std::vector<std::string>& made = rigged->report.made;
  EXPECT_NE(std::find(made.begin(), made.end(), "eyeLookOutLeft"), made.end());
  EXPECT_NE(std::find(made.begin(), made.end(), "eyeLookUpRight"), made.end());
  for (const eng::Mesh& mesh : rigged->model.meshes) {
    const auto au5 = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), "AU5_UpperLidRaiser");
    if (au5 == mesh.targetNames.end()) continue;
    const size_t t = size_t(au5 - mesh.targetNames.begin());
    float eyeMoves = 0.0f, skinMoves = 0.0f;
    for (const eng::Primitive& prim : mesh.primitives) {
      if (t >= prim.targets.size() || prim.targets[t].positions.empty()) continue;
      const bool eye = prim.material >= 0 && rigged->model.materials[size_t(prim.material)].name.find("a scan's") != std::string::npos;
      for (const glm::vec3& d : prim.targets[t].positions) (eye ? eyeMoves : skinMoves) = std::max(eye ? eyeMoves : skinMoves, glm::length(d));
    }
    EXPECT_GT(skinMoves, 0.1f * scan->source.parts.eyeRadii[0]) << "the upper lid rises";
    EXPECT_LT(eyeMoves, 1e-6f) << "the eye stays";
  }
}

}  // namespace
