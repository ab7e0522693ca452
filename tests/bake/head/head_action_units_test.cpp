// The built-in head's action-unit targets: canonical names on every part of
// the "Head" mesh, lids that close over the eyes (AU45) without cutting into
// them, a jaw that drops with the lower teeth (AU26), lips that part (AU25),
// one-sided units that stay on their side, mirror-image left/right pairs, and
// the speech units: lips that pucker, funnel and roll in, a wider jaw
// (AU27), and a tongue whose tip rises to the upper teeth (AU19).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "facial/runtime/rig/action_units.h"
#include "tests/bake/head/built_in_head.h"

namespace {

using bake::HeadPrimitive;
using head_testing::builtInHead;
using head_testing::headMesh;
using head_testing::headPrimitive;
using head_testing::landmark;
using head_testing::morphed;
using head_testing::targetIndex;

int target(const std::string& name) {
  const int t = targetIndex(headMesh(builtInHead().model), name);
  if (t < 0) throw std::runtime_error("no target " + name);
  return t;
}

float maxDelta(const eng::Primitive& prim, int t) {
  float m = 0.0f;
  for (const glm::vec3& d : prim.targets[t].positions) m = std::max(m, glm::length(d));
  return m;
}

TEST(HeadActionUnits, HeadMeshHasEveryCanonicalChannelInOrder) {
  const eng::Mesh& mesh = headMesh(builtInHead().model);
  const auto units = facial::actionUnits();
  ASSERT_EQ(mesh.targetNames.size(), units.size());
  for (size_t i = 0; i < units.size(); ++i) EXPECT_EQ(mesh.targetNames[i], units[i].name);
  EXPECT_EQ(mesh.defaultWeights, std::vector<float>(units.size(), 0.0f));
  for (const eng::Primitive& prim : mesh.primitives) {
    ASSERT_EQ(prim.targets.size(), units.size());
    for (const eng::MorphTarget& t : prim.targets) {
      EXPECT_EQ(t.positions.size(), prim.vertexCount());
      EXPECT_EQ(t.normals.size(), prim.vertexCount());
    }
  }
}

TEST(HeadActionUnits, EveryUnitMovesTheSkinVisibly) {
  const eng::Primitive& skin = headPrimitive(builtInHead().model, HeadPrimitive::Skin);
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) {
    if (info.facsNumber == 19) continue;  // the tongue's unit (TongueShowRaisesTheTipToTheUpperTeeth)
    EXPECT_GT(maxDelta(skin, target(std::string(info.name))), 0.002f) << info.name << " moves less than 2 mm";
  }
}

TEST(HeadActionUnits, BlinkBringsTheUpperLidDownToTheLowerLid) {
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  for (const char* side : {"L", "R"}) {
    const int blink = target(std::string("AU45_Blink_") + side);
    const glm::vec3 upper = landmark(head, std::string("lid_upper_") + side);
    const glm::vec3 lower = landmark(head, std::string("lid_lower_") + side);
    const size_t v = head_testing::nearestVertex(skin.positions, upper);
    ASSERT_LT(glm::length(skin.positions[v] - upper), 0.001f) << side << ": no lid vertex at the landmark";
    // The lid slides around the eyeball: compare directions from its centre,
    // and check the closed upper lid lies over (outside) the lower one.
    const head_testing::Eyeball eye = head_testing::eyeball(head.model, side[0] == 'L' ? 0 : 1);
    const glm::vec3 closed = skin.positions[v] + skin.targets[blink].positions[v];
    const float gapDegrees =
        glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(closed - eye.centre), glm::normalize(lower - eye.centre)), -1.0f, 1.0f)));
    EXPECT_LT(gapDegrees, 3.0f) << side << ": upper lid stops " << gapDegrees << " degrees from the lower lid";
    EXPECT_GE(glm::length(closed - eye.centre), glm::length(lower - eye.centre)) << side;
  }
}

TEST(HeadActionUnits, ClosedLidsHideTheWholeEyeball) {
  // Rays from the front through the open eye meet the eyeball at rest and the
  // lid skin once AU45 is fully on.
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  for (int e = 0; e < 2; ++e) {
    const std::string side = e == 0 ? "L" : "R";
    const eng::Primitive eye = head_testing::eyeballInHeadSpace(head.model, e);
    const std::vector<glm::vec3> closed = morphed(skin, target("AU45_Blink_" + side), 1.0f);
    const glm::vec3 inner = landmark(head, "eye_inner_corner_" + side), outer = landmark(head, "eye_outer_corner_" + side);
    const glm::vec3 upper = landmark(head, "lid_upper_" + side), lower = landmark(head, "lid_lower_" + side);
    int visibleAtRest = 0;
    for (int i = 1; i < 8; ++i) {
      const float f = i / 8.0f;
      const float x = glm::mix(inner.x, outer.x, f);
      const float y = glm::mix(lower.y, upper.y, 0.5f) + 0.15f * (upper.y - lower.y) * std::sin(f * 6.0f);
      const auto eyeZ = head_testing::frontHitZ(eye.positions, eye.indices, x, y);
      const auto restSkin = head_testing::frontHitZ(skin.positions, skin.indices, x, y);
      if (!eyeZ || !restSkin || *eyeZ <= *restSkin) continue;  // covered by a lid already
      ++visibleAtRest;
      const auto closedSkin = head_testing::frontHitZ(closed, skin.indices, x, y);
      ASSERT_TRUE(closedSkin.has_value());
      EXPECT_GT(*closedSkin, *eyeZ) << side << ": eyeball still visible at x " << x << ", y " << y;
    }
    EXPECT_GE(visibleAtRest, 5) << side;
  }
}

TEST(HeadActionUnits, LidsNeverSinkIntoTheEyeballs) {
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  for (int e = 0; e < 2; ++e) {
    const head_testing::Eyeball ball = head_testing::eyeball(head.model, e);
    const glm::vec3 centre = ball.centre;
    const float radius = ball.radius;
    for (const char* unit : {"AU45_Blink_L", "AU45_Blink_R", "AU5_UpperLidRaiser", "AU7_LidTightener", "AU6_CheekRaiser",
                             "AU4_BrowLowerer"}) {
      const std::vector<glm::vec3> moved = morphed(skin, target(unit), 1.0f);
      for (size_t v = 0; v < skin.vertexCount(); ++v) {
        const float rest = glm::length(skin.positions[v] - centre);
        if (rest < radius + 0.0003f || rest > radius + 0.004f) continue;  // tucked-in margin, or far away
        EXPECT_GT(glm::length(moved[v] - centre), radius) << unit << " pushes a lid vertex into eyeball " << e;
      }
    }
  }
}

TEST(HeadActionUnits, JawDropOpensTheMouthAndCarriesTheLowerTeeth) {
  const bake::GeneratedHead& head = builtInHead();
  const int jaw = target("AU26_JawDrop");
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  const size_t upperLip = head_testing::nearestVertex(skin.positions, landmark(head, "upper_lip_centre"));
  const size_t lowerLip = head_testing::nearestVertex(skin.positions, landmark(head, "lower_lip_centre"));
  const size_t chin = head_testing::nearestVertex(skin.positions, landmark(head, "chin"));
  EXPECT_LT(glm::length(skin.targets[jaw].positions[upperLip]), 0.001f);
  EXPECT_LT(skin.targets[jaw].positions[lowerLip].y, -0.010f);
  EXPECT_LT(skin.targets[jaw].positions[chin].y, -0.010f);
  // The lower teeth follow the jaw; the upper teeth stay with the skull.
  EXPECT_GT(maxDelta(headPrimitive(head.model, HeadPrimitive::TeethLower), jaw), 0.010f);
  EXPECT_EQ(maxDelta(headPrimitive(head.model, HeadPrimitive::TeethUpper), jaw), 0.0f);
  const eng::Primitive& lowerTeeth = headPrimitive(head.model, HeadPrimitive::TeethLower);
  for (size_t v = 0; v < lowerTeeth.vertexCount(); ++v)
    ASSERT_LT(lowerTeeth.targets[jaw].positions[v].y, -0.004f) << "lower tooth vertex " << v << " left behind";
  // The seam opens: rays through the middle of the mouth now reach the inside.
  const glm::vec3 seam = (landmark(head, "upper_lip_centre") + landmark(head, "lower_lip_centre")) * 0.5f;
  const std::vector<glm::vec3> open = morphed(skin, jaw, 1.0f);
  const auto restZ = head_testing::frontHitZ(skin.positions, skin.indices, 0.001f, seam.y);
  const auto openZ = head_testing::frontHitZ(open, skin.indices, 0.001f, seam.y - 0.002f);
  ASSERT_TRUE(restZ.has_value());
  EXPECT_TRUE(!openZ.has_value() || *openZ < *restZ - 0.01f)
      << "mouth still closed at the middle: skin at z " << openZ.value_or(0.0f) << ", at rest " << *restZ;
}

// Displacement of the skin vertex nearest a landmark under one unit.
glm::vec3 landmarkDelta(const std::string& unit, const std::string& name) {
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  return skin.targets[target(unit)].positions[head_testing::nearestVertex(skin.positions, landmark(head, name))];
}

TEST(HeadActionUnits, PuckerPushesTheLipsForwardAndTheCornersInward) {
  for (const char* lip : {"upper_lip_centre", "lower_lip_centre"})
    EXPECT_GT(landmarkDelta("AU18_LipPucker", lip).z, 0.005f) << lip;
  const glm::vec3 left = landmarkDelta("AU18_LipPucker", "mouth_corner_L"), right = landmarkDelta("AU18_LipPucker", "mouth_corner_R");
  EXPECT_LT(left.x, -0.005f);  // toward the middle from both sides
  EXPECT_GT(right.x, 0.005f);
  EXPECT_GT(left.z, 0.002f);
}

TEST(HeadActionUnits, FunnelerFlaresTheLipsForwardAndApart) {
  const glm::vec3 upper = landmarkDelta("AU22_LipFunneler", "upper_lip_centre");
  const glm::vec3 lower = landmarkDelta("AU22_LipFunneler", "lower_lip_centre");
  EXPECT_GT(upper.z, 0.004f);
  EXPECT_GT(lower.z, 0.004f);
  EXPECT_GT(upper.y - lower.y, 0.004f);  // the opening rounds: lips apart, corners in
  EXPECT_LT(landmarkDelta("AU22_LipFunneler", "mouth_corner_L").x, -0.003f);
}

TEST(HeadActionUnits, LipSuckRollsTheLipsInTowardTheTeeth) {
  const glm::vec3 upper = landmarkDelta("AU28_LipSuck", "upper_lip_centre");
  const glm::vec3 lower = landmarkDelta("AU28_LipSuck", "lower_lip_centre");
  EXPECT_LT(upper.z, -0.004f);
  EXPECT_LT(lower.z, -0.004f);
  EXPECT_LT(upper.y, -0.002f);
  EXPECT_GT(lower.y, 0.002f);
}

TEST(HeadActionUnits, MouthStretchStacksOnJawDropWithinItsReach) {
  // AU26 + AU27 open the jaw about twice as far as AU26; AU27 alone stays
  // within AU26's reach, so the framing bounds (every target at full weight)
  // and with them every render of the head do not move.
  const glm::vec3 stretch = landmarkDelta("AU27_MouthStretch", "chin"), drop = landmarkDelta("AU26_JawDrop", "chin");
  EXPECT_LT(stretch.y, 0.8f * drop.y);
  EXPECT_GE(stretch.y, drop.y - 1e-4f);
  EXPECT_GE(stretch.z, drop.z - 1e-4f);
  EXPECT_LT(landmarkDelta("AU27_MouthStretch", "mouth_corner_L").y, landmarkDelta("AU26_JawDrop", "mouth_corner_L").y);
  EXPECT_LT(glm::length(landmarkDelta("AU27_MouthStretch", "upper_lip_centre")), 0.001f);
  EXPECT_GT(maxDelta(headPrimitive(builtInHead().model, HeadPrimitive::TeethLower), target("AU27_MouthStretch")), 0.015f);
}

TEST(HeadActionUnits, JawThrustBringsTheChinAndLowerTeethForward) {
  EXPECT_GT(landmarkDelta("AU29_JawThrust", "chin").z, 0.003f);
  EXPECT_GT(landmarkDelta("AU29_JawThrust", "lower_lip_centre").z, 0.003f);
  EXPECT_LT(glm::length(landmarkDelta("AU29_JawThrust", "upper_lip_centre")), 0.001f);
  const eng::Primitive& lower = headPrimitive(builtInHead().model, HeadPrimitive::TeethLower);
  const int t = target("AU29_JawThrust");
  for (size_t v = 0; v < lower.vertexCount(); ++v) ASSERT_GT(lower.targets[t].positions[v].z, 0.002f) << "lower tooth vertex " << v;
}

TEST(HeadActionUnits, TongueShowRaisesTheTipToTheUpperTeeth) {
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& tongue = headPrimitive(head.model, HeadPrimitive::Tongue);
  const int t = target("AU19_TongueShow");
  size_t tip = 0, back = 0;
  for (size_t v = 0; v < tongue.vertexCount(); ++v) {
    if (tongue.positions[v].z > tongue.positions[tip].z) tip = v;
    if (tongue.positions[v].z < tongue.positions[back].z) back = v;
  }
  const glm::vec3 moved = tongue.positions[tip] + tongue.targets[t].positions[tip];
  const glm::vec3 incisor = landmark(head, "upper_incisor");
  EXPECT_GT(tongue.targets[t].positions[tip].y, 0.004f);  // up
  EXPECT_GT(tongue.targets[t].positions[tip].z, 0.0f);    // and forward
  EXPECT_LT(std::abs(moved.y - incisor.y), 0.004f) << "the tip ends " << (moved.y - incisor.y) * 1000.0f << " mm from the incisor edge";
  EXPECT_LT(moved.z, incisor.z) << "the tip ends in front of the upper teeth";
  EXPECT_EQ(glm::length(tongue.targets[t].positions[back]), 0.0f);  // the root stays
  // Only the tongue moves.
  for (HeadPrimitive p : {HeadPrimitive::Skin, HeadPrimitive::Mouth, HeadPrimitive::TeethUpper, HeadPrimitive::TeethLower})
    EXPECT_EQ(maxDelta(headPrimitive(head.model, p), t), 0.0f) << int(p);
}

TEST(HeadActionUnits, NoOtherUnitMovesTheTeeth) {
  const eng::Model& model = builtInHead().model;
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) {
    if (info.name == "AU26_JawDrop" || info.name == "AU27_MouthStretch" || info.name == "AU29_JawThrust") continue;  // the jaw units
    const int t = target(std::string(info.name));
    EXPECT_EQ(maxDelta(headPrimitive(model, HeadPrimitive::TeethUpper), t), 0.0f) << info.name;
    EXPECT_EQ(maxDelta(headPrimitive(model, HeadPrimitive::TeethLower), t), 0.0f) << info.name;
  }
}

TEST(HeadActionUnits, LipsPartSeparatesTheSeamSides) {
  const bake::GeneratedHead& head = builtInHead();
  const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
  const int part = target("AU25_LipsPart");
  const glm::vec3 seam = (landmark(head, "upper_lip_centre") + landmark(head, "lower_lip_centre")) * 0.5f;
  // The two coincident seam vertices nearest the middle move apart vertically.
  float bestUp = 0.0f, bestDown = 0.0f;
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    if (std::abs(skin.positions[v].x) > 0.003f || std::abs(skin.positions[v].y - seam.y) > 0.004f) continue;
    bestUp = std::max(bestUp, skin.targets[part].positions[v].y);
    bestDown = std::min(bestDown, skin.targets[part].positions[v].y);
  }
  EXPECT_GT(bestUp - bestDown, 0.005f);
}

TEST(HeadActionUnits, OneSidedUnitsStayOnTheirSide) {
  const eng::Primitive& skin = headPrimitive(builtInHead().model, HeadPrimitive::Skin);
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) {
    if (info.side == facial::FaceSide::Both) continue;
    const int t = target(std::string(info.name));
    const float wrongSide = info.side == facial::FaceSide::Left ? -1.0f : 1.0f;
    float across = 0.0f, own = 0.0f;
    for (size_t v = 0; v < skin.vertexCount(); ++v) {
      const float len = glm::length(skin.targets[t].positions[v]);
      if (skin.positions[v].x * wrongSide > 0.008f) across = std::max(across, len);
      if (skin.positions[v].x * wrongSide < -0.008f) own = std::max(own, len);
    }
    EXPECT_EQ(across, 0.0f) << info.name << " moves the other side";
    EXPECT_GT(own, 0.002f) << info.name;
  }
}

TEST(HeadActionUnits, LeftAndRightUnitsAreMirrorImages) {
  const eng::Primitive& skin = headPrimitive(builtInHead().model, HeadPrimitive::Skin);
  for (const char* base : {"AU2_OuterBrowRaiser", "AU12_LipCornerPuller", "AU45_Blink"}) {
    const int l = target(std::string(base) + "_L"), r = target(std::string(base) + "_R");
    // Compare at the vertex of each side that moves most.
    size_t vl = 0;
    for (size_t v = 0; v < skin.vertexCount(); ++v)
      if (glm::length(skin.targets[l].positions[v]) > glm::length(skin.targets[l].positions[vl])) vl = v;
    const glm::vec3 mirrorPoint(-skin.positions[vl].x, skin.positions[vl].y, skin.positions[vl].z);
    const size_t vr = head_testing::nearestVertex(skin.positions, mirrorPoint);
    ASSERT_LT(glm::length(skin.positions[vr] - mirrorPoint), 1e-5f) << base << ": the skin is not mirror-symmetric";
    const glm::vec3 dl = skin.targets[l].positions[vl], dr = skin.targets[r].positions[vr];
    // Each side's RBF system is solved on its own: rounding differs slightly.
    EXPECT_NEAR(dl.x, -dr.x, 5e-5f) << base;
    EXPECT_NEAR(dl.y, dr.y, 5e-5f) << base;
    EXPECT_NEAR(dl.z, dr.z, 5e-5f) << base;
  }
}

TEST(HeadActionUnits, NormalDeltasFollowTheShapeChange) {
  // A jaw drop turns the chin's surface: its normal deltas are not all zero,
  // and base + delta stays close to unit length.
  const eng::Primitive& skin = headPrimitive(builtInHead().model, HeadPrimitive::Skin);
  const int jaw = target("AU26_JawDrop");
  size_t changed = 0;
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    const glm::vec3 dn = skin.targets[jaw].normals[v];
    if (dn == glm::vec3(0.0f)) continue;
    ++changed;
    EXPECT_NEAR(glm::length(skin.normals[v] + dn), 1.0f, 1e-3f);
  }
  EXPECT_GT(changed, 500u);
}

}  // namespace
