// The ARKit shapes made from a face's geometry (gaze, jaw and mouth sideways,
// mouthClose, cheekPuff, dimples): what each does to the built-in head rigged
// onto itself, and which are left out when the face lacks what they need.
// facecap_ground_truth_test.cpp measures them against a real capture.
#include "autorig/arkit_from_geometry.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "autorig/target_transfer.h"
#include "facial/runtime/character/gaze_rig.h"
#include "tests/autorig/transfer_fixture.h"

namespace {

using autorig::FacePart;

struct RiggedHead {
  eng::Model head;  // the source's model lives here
  autorig::SourceFace source;
  eng::Model model;  // the head stripped, then rigged from itself
  std::vector<FacePart> parts;  // per posed vertex, primitives in order
  std::vector<glm::vec3> positions;
};

const RiggedHead* riggedHead() {
  static std::optional<RiggedHead> cached;
  static bool tried = false;
  if (tried) return cached ? &*cached : nullptr;
  tried = true;
  std::optional<eng::Model> head = transfer_fixture::loadHead();
  if (!head) return nullptr;
  cached.emplace();
  cached->head = std::move(*head);
  cached->source = transfer_fixture::headSource(cached->head);
  const autorig::SourceFace& s = cached->source;
  eng::Result<autorig::TransferResult> result =
      autorig::transferTargets(s, transfer_fixture::stripped(cached->head), s.posed, s.landmarks, s.parts,
                               transfer_fixture::kShapesOnly);
  if (!result) {
    ADD_FAILURE() << result.error().message;
    cached.reset();
    return nullptr;
  }
  cached->model = std::move(result->model);
  for (size_t i = 0; i < s.posed.primitives.size(); ++i) {
    const autorig::PosedPrimitive& p = s.posed.primitives[i];
    cached->positions.insert(cached->positions.end(), p.positions.begin(), p.positions.end());
    cached->parts.insert(cached->parts.end(), s.parts.vertexParts[i].begin(), s.parts.vertexParts[i].end());
  }
  return &*cached;
}

// A made target's world-space displacement of every posed vertex (zero on
// meshes it does not move).
std::vector<glm::vec3> headDeltas(const RiggedHead& r, const std::string& target) {
  std::vector<glm::vec3> out;
  for (const autorig::PosedPrimitive& p : r.source.posed.primitives) {
    const eng::Mesh& mesh = r.model.meshes[p.mesh];
    const auto t = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), target);
    for (size_t v = 0; v < p.positions.size(); ++v) {
      glm::vec3 d(0.0f);
      if (t != mesh.targetNames.end())
        d = glm::inverse(p.worldToLocal[v]) * mesh.primitives[p.primitive].targets[size_t(t - mesh.targetNames.begin())].positions[v];
      out.push_back(d);
    }
  }
  return out;
}

size_t nearestHeadSkin(const RiggedHead& r, const glm::vec3& point) {
  size_t best = 0;
  float bestDistance = INFINITY;
  for (size_t v = 0; v < r.positions.size(); ++v)
    if (r.parts[v] == FacePart::Skin && glm::distance(r.positions[v], point) < bestDistance)
      best = v, bestDistance = glm::distance(r.positions[v], point);
  return best;
}

TEST(ArkitFromGeometry, GazeTurnsOneEyeballAboutItsCentreAndTheLidsFollowIt) {
  const RiggedHead* r = riggedHead();
  ASSERT_NE(r, nullptr);
  const autorig::FaceParts& parts = r->source.parts;
  ASSERT_TRUE(parts.eyeballsFound);
  const autorig::LandmarkFrame frame(r->source.landmarks);
  const auto& l = r->source.landmarks.points;
  struct Look {
    const char* name;
    int eye;
    glm::vec3 toward;
    size_t upperLid;  // a landmark on that eye's upper lid
  };
  const Look looks[] = {
      {"eyeLookUpLeft", 1, frame.up(), 44},       {"eyeLookDownLeft", 1, -frame.up(), 44},
      {"eyeLookInLeft", 1, -frame.side(), 44},    {"eyeLookOutLeft", 1, frame.side(), 44},
      {"eyeLookUpRight", 0, frame.up(), 37},      {"eyeLookDownRight", 0, -frame.up(), 37},
      {"eyeLookInRight", 0, frame.side(), 37},    {"eyeLookOutRight", 0, -frame.side(), 37},
  };
  for (const Look& look : looks) {
    SCOPED_TRACE(look.name);
    const std::vector<glm::vec3> d = headDeltas(*r, look.name);
    const FacePart ball = look.eye == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
    const FacePart other = look.eye == 0 ? FacePart::EyeballLeft : FacePart::EyeballRight;
    const glm::vec3 centre = parts.eyeCentres[size_t(look.eye)];
    const float radius = parts.eyeRadii[size_t(look.eye)];
    size_t front = 0;
    float frontDepth = -INFINITY;
    for (size_t v = 0; v < d.size(); ++v) {
      if (r->parts[v] == other) {
        EXPECT_EQ(d[v], glm::vec3(0.0f));
      }
      if (r->parts[v] != ball) continue;
      // A turn: every point of the ball keeps its distance to the centre.
      EXPECT_NEAR(glm::distance(r->positions[v] + d[v], centre), glm::distance(r->positions[v], centre), 1e-3f * radius);
      const float depth = glm::dot(r->positions[v] - centre, frame.forward());
      if (depth > frontDepth) frontDepth = depth, front = v;
    }
    ASSERT_GT(frontDepth, 0.0f);
    // The pupil goes the named way by the ball's reach at kArkitLookDegrees.
    const float reach = frontDepth * std::sin(glm::radians(facial::kArkitLookDegrees));
    EXPECT_NEAR(glm::dot(d[front], look.toward), reach, 0.1f * reach);
    // The upper lid goes the same way, less far; the brow stays.
    const float lid = glm::dot(d[nearestHeadSkin(*r, l[look.upperLid])], look.toward);
    EXPECT_GT(lid, 0.2f * reach);
    EXPECT_LT(lid, reach);
    const size_t brow = look.eye == 0 ? 19 : 24;
    EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[brow])]), 0.05f * reach);
  }
}

// ARKit's mouthClose is played over jawOpen: the lips meet, the chin stays down.
TEST(ArkitFromGeometry, MouthCloseOverJawOpenClosesTheLips) {
  const RiggedHead* r = riggedHead();
  ASSERT_NE(r, nullptr);
  const autorig::LandmarkFrame frame(r->source.landmarks);
  const auto& l = r->source.landmarks.points;
  const std::vector<glm::vec3> open = headDeltas(*r, "jawOpen"), close = headDeltas(*r, "mouthClose");
  const size_t upper = nearestHeadSkin(*r, l[51]), lower = nearestHeadSkin(*r, l[57]), chin = nearestHeadSkin(*r, l[8]);
  auto gap = [&](float closed) {
    return glm::dot((r->positions[upper] + open[upper] + closed * close[upper]) -
                        (r->positions[lower] + open[lower] + closed * close[lower]),
                    frame.up());
  };
  const float rest = glm::dot(r->positions[upper] - r->positions[lower], frame.up());
  std::printf("lip gap: rest %.4f, jawOpen %.4f, jawOpen + mouthClose %.4f\n", rest, gap(0.0f), gap(1.0f));
  EXPECT_GT(gap(0.0f) - rest, 0.1f * frame.eyeSpan());
  EXPECT_LT(std::abs(gap(1.0f) - rest), 0.15f * (gap(0.0f) - rest));
  // The chin keeps most of its drop.
  EXPECT_LT(glm::length(close[chin]), 0.25f * glm::length(open[chin]));
}

TEST(ArkitFromGeometry, JawAndMouthGoToTheNamedSideOrForward) {
  const RiggedHead* r = riggedHead();
  ASSERT_NE(r, nullptr);
  const autorig::LandmarkFrame frame(r->source.landmarks);
  const auto& l = r->source.landmarks.points;
  const float span = frame.eyeSpan();
  for (const auto& [name, sign] : {std::pair{"jawLeft", 1.0f}, std::pair{"jawRight", -1.0f}}) {
    SCOPED_TRACE(name);
    const std::vector<glm::vec3> d = headDeltas(*r, name);
    EXPECT_NEAR(glm::dot(d[nearestHeadSkin(*r, l[8])], frame.side()), sign * 0.1f * span, 0.02f * span);
    EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[30])]), 0.01f * span);  // the nose tip
    float lowerTeeth = 0.0f, upperTeeth = 0.0f;
    for (size_t v = 0; v < d.size(); ++v) {
      if (r->parts[v] == FacePart::LowerTeeth) lowerTeeth = std::max(lowerTeeth, sign * glm::dot(d[v], frame.side()));
      if (r->parts[v] == FacePart::UpperTeeth) upperTeeth = std::max(upperTeeth, glm::length(d[v]));
    }
    EXPECT_GT(lowerTeeth, 0.05f * span);
    EXPECT_EQ(upperTeeth, 0.0f);
  }
  {
    // jawForward: the whole jaw slides forward (and a little down), the
    // lower teeth with it: not only the chin, as the head's AU29 pushes it.
    const std::vector<glm::vec3> d = headDeltas(*r, "jawForward");
    const glm::vec3 chin = d[nearestHeadSkin(*r, l[8])];
    EXPECT_NEAR(glm::dot(chin, frame.forward()), 0.104f * span, 0.02f * span);
    EXPECT_LT(glm::dot(chin, frame.up()), 0.0f);
    EXPECT_GT(glm::dot(d[nearestHeadSkin(*r, l[6])], frame.forward()), 0.5f * glm::dot(chin, frame.forward()));  // the jaw line
    EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[30])]), 0.01f * span);
    float lowerTeeth = 0.0f;
    for (size_t v = 0; v < d.size(); ++v)
      if (r->parts[v] == FacePart::LowerTeeth) lowerTeeth = std::max(lowerTeeth, glm::dot(d[v], frame.forward()));
    EXPECT_GT(lowerTeeth, 0.05f * span);
  }
  {
    // mouthShrugUpper: the upper lip up as one piece, the lower lip, the
    // nose's base and the inside of the mouth still.
    const std::vector<glm::vec3> d = headDeltas(*r, "mouthShrugUpper");
    EXPECT_NEAR(glm::dot(d[nearestHeadSkin(*r, l[51])], frame.up()), 0.055f * span, 0.01f * span);
    EXPECT_GT(glm::dot(d[nearestHeadSkin(*r, l[62])], frame.up()), 0.02f * span);  // the inner rim goes too
    for (size_t still : {57, 66, 8, 33}) EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[still])]), 0.01f * span) << still;
    for (size_t v = 0; v < d.size(); ++v)
      if (r->parts[v] != FacePart::Skin && r->parts[v] != FacePart::Lashes) {
        ASSERT_EQ(d[v], glm::vec3(0.0f));
      }
  }
  for (const auto& [name, sign] : {std::pair{"mouthLowerDownLeft", 1.0f}, std::pair{"mouthLowerDownRight", -1.0f}}) {
    // One half of the lower lip down and back; the other half, the upper
    // lip, the chin and the teeth still.
    SCOPED_TRACE(name);
    const std::vector<glm::vec3> d = headDeltas(*r, name);
    const glm::vec3 own = d[nearestHeadSkin(*r, glm::mix(l[57], sign > 0.0f ? l[55] : l[59], 0.5f))];
    const glm::vec3 other = d[nearestHeadSkin(*r, glm::mix(l[57], sign > 0.0f ? l[59] : l[55], 0.5f))];
    EXPECT_LT(glm::dot(own, frame.up()), -0.05f * span);
    EXPECT_LT(glm::dot(own, frame.forward()), 0.0f);
    EXPECT_LT(glm::length(other), 0.3f * glm::length(own));
    for (size_t still : {51, 8}) EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[still])]), 0.01f * span) << still;
    for (size_t v = 0; v < d.size(); ++v)
      if (r->parts[v] != FacePart::Skin && r->parts[v] != FacePart::Lashes) {
        ASSERT_EQ(d[v], glm::vec3(0.0f));
      }
  }
  for (const auto& [name, sign] : {std::pair{"mouthLeft", 1.0f}, std::pair{"mouthRight", -1.0f}}) {
    SCOPED_TRACE(name);
    const std::vector<glm::vec3> d = headDeltas(*r, name);
    for (size_t corner : {48, 54, 51, 57}) EXPECT_GT(sign * glm::dot(d[nearestHeadSkin(*r, l[corner])], frame.side()), 0.08f * span) << corner;
    for (size_t still : {30, 8, 37, 44}) EXPECT_LT(glm::length(d[nearestHeadSkin(*r, l[still])]), 0.02f * span) << still;
    for (size_t v = 0; v < d.size(); ++v)
      if (r->parts[v] == FacePart::LowerTeeth || r->parts[v] == FacePart::UpperTeeth) {
        ASSERT_EQ(d[v], glm::vec3(0.0f));
      }
  }
  for (const auto& [name, corner] : {std::pair{"mouthDimpleLeft", 54}, std::pair{"mouthDimpleRight", 48}}) {
    const glm::vec3 d = headDeltas(*r, name)[nearestHeadSkin(*r, l[size_t(corner)])];
    EXPECT_LT(glm::dot(d, frame.forward()), -0.05f * span) << name << ": the corner goes back";
  }
  const std::vector<glm::vec3> puff = headDeltas(*r, "cheekPuff");
  const glm::vec3 cheek = glm::mix(l[54], l[12], 0.2f);
  EXPECT_GT(glm::dot(puff[nearestHeadSkin(*r, cheek)], frame.forward()), 0.05f * span);
  EXPECT_LT(glm::length(puff[nearestHeadSkin(*r, l[30])]), 0.02f * span);
}

// cheekSquint raises the cheek and leaves the lids to eyeSquint: AU6 does
// both, and a smile streamed with both closed the eyes twice over.
TEST(ArkitFromUnits, CheekSquintRaisesTheCheekAndLeavesTheLids) {
  const RiggedHead* r = riggedHead();
  ASSERT_NE(r, nullptr);
  const autorig::LandmarkFrame frame(r->source.landmarks);
  const auto& l = r->source.landmarks.points;
  const std::vector<glm::vec3> cheek = headDeltas(*r, "cheekSquintLeft"), squint = headDeltas(*r, "eyeSquintLeft");
  float cheekRise = 0.0f;
  for (size_t v = 0; v < cheek.size(); ++v) cheekRise = std::max(cheekRise, glm::dot(cheek[v], frame.up()));
  EXPECT_GT(cheekRise, 0.02f * frame.eyeSpan());
  for (size_t lid : {46, 47}) {  // the left eye's lower lid
    const size_t v = nearestHeadSkin(*r, l[lid]);
    EXPECT_LT(glm::length(cheek[v]), 0.1f * cheekRise) << lid;
    EXPECT_GT(glm::dot(squint[v], frame.up()), 0.2f * cheekRise) << lid << ": eyeSquint raises it";
  }
}

// Validity: what a face lacks, the shapes that need it are named, not made.
TEST(ArkitFromGeometryValidity, ShapesWhoseSourceIsMissingAreNamedUnmade) {
  const RiggedHead* r = riggedHead();
  ASSERT_NE(r, nullptr);
  const autorig::LandmarkFrame frame(r->source.landmarks);
  autorig::FaceParts noEyeballs = r->source.parts;
  noEyeballs.eyeballsFound = false;
  const std::vector<std::string> wanted = {"eyeLookUpLeft", "jawLeft",     "jawForward", "mouthShrugUpper", "mouthLowerDownLeft",
                                           "mouthClose",    "mouthLeft",   "cheekPuff",  "mouthDimpleLeft", "browInnerUp"};
  const autorig::ShapeGeometry geometry{.positions = r->positions, .parts = r->parts, .normals = {},
                                        .landmarks = &r->source.landmarks, .frame = &frame, .faceParts = &noEyeballs};
  std::vector<std::string> unmade;
  const std::vector<autorig::NamedDeltas> made = autorig::arkitFromGeometry(wanted, {}, geometry, unmade);
  EXPECT_EQ(unmade, (std::vector<std::string>{"eyeLookUpLeft", "jawLeft", "jawForward", "mouthShrugUpper", "mouthLowerDownLeft",
                                              "mouthClose", "browInnerUp"}));
  ASSERT_EQ(made.size(), 3u);
  EXPECT_EQ(made[0].name, "mouthLeft");
  for (const autorig::NamedDeltas& shape : made) EXPECT_EQ(shape.deltas.size(), r->positions.size());

  // A scan's eye, painted on the skin inside its lids, is not turned: the
  // gaze shapes of that eye are named unmade, the other eye's are made.
  unmade.clear();
  autorig::FaceParts scanEye = r->source.parts;
  scanEye.eyesInTheSkin[1] = true;
  autorig::ShapeGeometry scan = geometry;
  scan.faceParts = &scanEye;
  const std::vector<std::string> bothLooks = {"eyeLookUpLeft", "eyeLookUpRight"};
  const std::vector<autorig::NamedDeltas> looks = autorig::arkitFromGeometry(bothLooks, {}, scan, unmade);
  EXPECT_EQ(unmade, (std::vector<std::string>{"eyeLookUpLeft"}));
  ASSERT_EQ(looks.size(), 1u);
  EXPECT_EQ(looks[0].name, "eyeLookUpRight");

  // Parts that do not match the positions: nothing is made.
  unmade.clear();
  autorig::ShapeGeometry mismatched = geometry;
  mismatched.parts = std::span<const FacePart>(r->parts).first(10);
  EXPECT_TRUE(autorig::arkitFromGeometry(wanted, {}, mismatched, unmade).empty());
  EXPECT_EQ(unmade.size(), wanted.size());
}

}  // namespace
