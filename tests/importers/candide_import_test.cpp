// CANDIDE-3 import: the distributed mask (../shared/candide3) becomes one
// morphable mesh with FACS-named animation units and SU_ identity targets;
// malformed files fail with file:line messages.
#include "importers/candide_import.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "importers/procedural_eyes.h"
#include "facial/runtime/rig/candide_units.h"
#include "facial/runtime/rig/rig_calibration.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/rig/action_units.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

std::filesystem::path candideFile() { return testing_support::sharedDir() / "candide3" / "candide3.wfm"; }

int targetIndex(const eng::Mesh& mesh, std::string_view name) {
  const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), name);
  return it == mesh.targetNames.end() ? -1 : static_cast<int>(it - mesh.targetNames.begin());
}

TEST(Candide3Import, LoadsTheDistributedMaskWithItsCounts) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(candideFile());
  ASSERT_TRUE(model) << model.error().message;
  EXPECT_TRUE(model->warnings.empty()) << model->warnings.front();
  ASSERT_EQ(model->meshes.size(), 1u);
  ASSERT_EQ(model->nodes.size(), 1u);
  EXPECT_EQ(model->nodes[0].mesh, 0);
  EXPECT_EQ(model->roots, std::vector<int>{0});
  const eng::Mesh& mesh = model->meshes[0];
  ASSERT_EQ(mesh.primitives.size(), 3u);  // the mask and its two eyeballs
  const eng::Primitive& prim = mesh.primitives[0];
  EXPECT_EQ(prim.vertexCount(), 113u);
  EXPECT_EQ(prim.indices.size(), (184u - 28u) * 3u);  // 14 triangles of skin inside each eye opening are cut
  EXPECT_EQ(prim.normals.size(), 113u);
  EXPECT_EQ(prim.texcoords.size(), 113u);
  EXPECT_EQ(mesh.targetNames.size(), 14u + 38u);
  EXPECT_EQ(prim.targets.size(), 14u + 38u);
  EXPECT_EQ(mesh.defaultWeights, std::vector<float>(52, 0.0f));

  size_t animationUnits = 0, shapeUnits = 0;
  for (const std::string& name : mesh.targetNames) {
    if (name.rfind("SU_", 0) == 0) ++shapeUnits;
    else if (name.rfind("AU", 0) == 0) ++animationUnits;
  }
  EXPECT_EQ(animationUnits, 14u);
  EXPECT_EQ(shapeUnits, 38u);
  for (const CandideAnimationUnit& unit : candideAnimationUnits())
    EXPECT_GE(targetIndex(mesh, candideTargetName(unit)), 0) << candideTargetName(unit);
  EXPECT_EQ(mesh.targetNames[0], "AU9 Nose wrinkler");
  EXPECT_EQ(mesh.targetNames[3], "AU26 Jaw drop");
  EXPECT_EQ(mesh.targetNames[14], "SU_Head height");
  EXPECT_EQ(mesh.targetNames.back(), "SU_Jaw z-position");
}

TEST(Candide3Import, MorphDeltasMatchTheFile) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(candideFile());
  ASSERT_TRUE(model) << model.error().message;
  const eng::Mesh& mesh = model->meshes[0];
  const eng::Primitive& prim = mesh.primitives[0];
  // "# Jaw drop": vertex 40 moves (0, -0.26, -0.05); vertex 0 (top of the head) does not.
  const eng::MorphTarget& jaw = prim.targets[size_t(targetIndex(mesh, "AU26 Jaw drop"))];
  EXPECT_FLOAT_EQ(jaw.positions[40].y, -0.26f);
  EXPECT_FLOAT_EQ(jaw.positions[40].z, -0.05f);
  EXPECT_EQ(jaw.positions[0], glm::vec3(0.0f));
  EXPECT_EQ(jaw.positions.size(), 113u);
  EXPECT_EQ(jaw.normals.size(), 113u);
  // Vertex 3 is listed twice in "# Outer brow raiser" (x +0.02 and -0.02): the entries add up.
  const eng::MorphTarget& brow = prim.targets[size_t(targetIndex(mesh, "AU2 Outer brow raiser"))];
  EXPECT_NEAR(brow.positions[3].x, 0.0f, 1e-7f);
  EXPECT_NEAR(brow.positions[3].y, 0.04f, 1e-6f);
  // Vertex 0 at the file's coordinates.
  EXPECT_EQ(prim.positions[0], glm::vec3(0.0f, 1.061f, -0.371f));
}

// The ball's surface depth at (x, y), or -inf outside its outline.
float ballFront(const glm::vec3& centre, float radius, glm::vec2 xy) {
  const float d2 = glm::dot(xy - glm::vec2(centre), xy - glm::vec2(centre));
  return d2 < radius * radius ? centre.z + std::sqrt(radius * radius - d2) : -INFINITY;
}

TEST(Candide3Import, EyeOpeningsAreCutAndEyeballsSitBehindTheLids) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(candideFile());
  ASSERT_TRUE(model) << model.error().message;
  const eng::Mesh& mesh = model->meshes[0];
  ASSERT_EQ(mesh.primitives.size(), 3u);
  const eng::Primitive& mask = mesh.primitives[0];
  // The skin between the lids (the file's vertices 67-74) is no longer drawn; the vertices stay, unused,
  // so the file's vertex numbers still name the same points.
  for (uint32_t i : mask.indices) EXPECT_TRUE(i < 67 || i > 74) << i;
  EXPECT_EQ(mask.positions[67], glm::vec3(0.348f, 0.2f, -0.03f));

  // The dressing finds both balls as eyeballs (by their material), and dresses no eyeball as skin.
  const std::vector<importers::EyePrimitive> eyes = importers::findUntexturedEyes(*model);
  ASSERT_EQ(eyes.size(), 2u);
  const eng::MorphTarget& eyesClosed = mask.targets[size_t(targetIndex(mesh, "AU45 Eyes closed"))];
  const eng::MorphTarget& eyesLower = mask.targets[size_t(targetIndex(mesh, "SU_Eyes vertical position"))];
  // Each eye's lid margins (the file's rims) and corners, from its inner corner round.
  const std::vector<uint32_t> rims[2] = {{23, 105, 21, 97, 20, 99, 22, 107}, {56, 106, 54, 98, 53, 100, 55, 108}};
  for (const importers::EyePrimitive& eye : eyes) {
    EXPECT_EQ(eye.mesh, 0);
    EXPECT_NEAR(eye.gazeAxis.z, 1.0f, 1e-6f);
    const std::vector<uint32_t>& rim = rims[eye.centre.x > 0.0f ? 0 : 1];
    const eng::Primitive& ball = mesh.primitives[size_t(eye.primitive)];
    for (uint32_t v : rim) {
      // Every margin lies over the ball (it fills the opening seen from the front) and in front of it,
      // open and with the lids closed.
      const glm::vec3 open = mask.positions[v], closed = open + eyesClosed.positions[v];
      EXPECT_GT(ballFront(eye.centre, eye.radius, open), -INFINITY) << v;
      EXPECT_GE(open.z, ballFront(eye.centre, eye.radius, open)) << v;
      EXPECT_GE(closed.z, ballFront(eye.centre, eye.radius, closed)) << v;
    }
    // An expression leaves the ball still; an identity shape carries it with its rim.
    const eng::MorphTarget& ballClosed = ball.targets[size_t(targetIndex(mesh, "AU45 Eyes closed"))];
    for (const glm::vec3& d : ballClosed.positions) EXPECT_EQ(d, glm::vec3(0.0f));
    glm::vec3 rimShift(0.0f);
    for (uint32_t v : rim) rimShift += eyesLower.positions[v] / float(rim.size());
    const eng::MorphTarget& ballLower = ball.targets[size_t(targetIndex(mesh, "SU_Eyes vertical position"))];
    EXPECT_NE(rimShift, glm::vec3(0.0f));
    for (const glm::vec3& d : ballLower.positions) EXPECT_EQ(d, rimShift);
    // A shape that widens the opening (its corners 0.1 out each, from 0.34) grows the ball with it: the
    // widened rim still lies over the ball and in front of it.
    const int widen = targetIndex(mesh, "SU_Eyes width");
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t k = 0; k < ball.positions.size(); ++k) {
      const glm::vec3 p = ball.positions[k] + ball.targets[size_t(widen)].positions[k];
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const glm::vec3 wideCentre = 0.5f * (lo + hi);
    const float wideRadius = 0.5f * (hi.x - lo.x);
    EXPECT_GT(wideRadius, eye.radius * 1.3f);
    for (uint32_t v : rim) {
      const glm::vec3 wide = mask.positions[v] + mask.targets[size_t(widen)].positions[v];
      EXPECT_GT(ballFront(wideCentre, wideRadius, wide), -INFINITY) << v;
      EXPECT_GE(wide.z, ballFront(wideCentre, wideRadius, wide)) << v;
    }
  }
  EXPECT_LT(eyes[0].centre.x * eyes[1].centre.x, 0.0f);  // one each side
}

TEST(Candide3Import, TrianglesFaceTheViewerAndNormalsAreUnit) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(candideFile());
  ASSERT_TRUE(model) << model.error().message;
  const eng::Primitive& prim = model->meshes[0].primitives[0];
  // Counter-clockwise seen from +z: the nose tip region's normal points at the viewer.
  float facing = 0.0f;
  for (size_t i = 0; i < prim.indices.size(); i += 3) {
    const glm::vec3 &a = prim.positions[prim.indices[i]], &b = prim.positions[prim.indices[i + 1]],
                    &c = prim.positions[prim.indices[i + 2]];
    facing += glm::cross(b - a, c - a).z;
  }
  EXPECT_GT(facing, 0.0f);
  for (const glm::vec3& n : prim.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  EXPECT_GT(prim.normals[5].z, 0.5f);  // vertex 5: the nose tip (0, -0.222, 0.21)
}

TEST(Candide3Import, ImportedNamesAreDetectedAsTheCandideScheme) {
  FACIAL_REQUIRE_SHARED();
  auto model = importers::importCandide3(candideFile());
  ASSERT_TRUE(model) << model.error().message;
  const std::vector<std::string>& names = model->meshes[0].targetNames;
  auto mapping = buildRigMapping(names);
  ASSERT_TRUE(mapping) << mapping.error().message;
  EXPECT_EQ(mapping->scheme(), RigScheme::Candide3);
  // The 38 identity targets and the two jaw pushes are reported, not driven.
  EXPECT_EQ(mapping->report().unmappedTargets.size(), 38u + 2u);
  EXPECT_NE(std::find(mapping->report().unmappedTargets.begin(), mapping->report().unmappedTargets.end(),
                      "SU_Head height"),
            mapping->report().unmappedTargets.end());

  // A smile (AU12 both sides) runs the lip corner depressor backwards.
  std::vector<float> au(actionUnits().size(), 0.0f);
  au[*actionUnitIndex("AU12_LipCornerPuller_L")] = 1.0f;
  au[*actionUnitIndex("AU12_LipCornerPuller_R")] = 1.0f;
  std::vector<float> weights(names.size(), 0.25f);
  ASSERT_TRUE(mapping->apply(au, weights));
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "AU15 Lip corner depressor"))], -1.0f);
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "AU26 Jaw drop"))], 0.0f);
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "SU_Head height"))], 0.25f);  // untouched

  // A lip stretcher also draws the corners down: the stretcher and half the depressor.
  std::fill(au.begin(), au.end(), 0.0f);
  au[*actionUnitIndex("AU20_LipStretcher")] = 0.5f;
  ASSERT_TRUE(mapping->apply(au, weights));
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "AU20 Lip stretcher"))], 0.5f);
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "AU15 Lip corner depressor"))], 0.25f);

  // The units are linear offsets: a weak one is raised past 1 by the strength
  // calibration, as far as its largest scale, instead of being clamped back to 1.
  const float maxScale = RigCalibrationOptions{}.maxScale;
  EXPECT_FLOAT_EQ(mapping->minWeight(), -maxScale);
  EXPECT_FLOAT_EQ(mapping->maxWeight(), maxScale);
  auto calibrated = calibrateRig(*mapping, std::vector<float>(names.size(), 1e-3f));
  ASSERT_TRUE(calibrated) << calibrated.error().message;
  std::fill(au.begin(), au.end(), 0.0f);
  au[*actionUnitIndex("AU26_JawDrop")] = 1.0f;
  ASSERT_TRUE(calibrated->rig.apply(au, weights));
  EXPECT_FLOAT_EQ(weights[size_t(targetIndex(model->meshes[0], "AU26 Jaw drop"))], 0.7f * maxScale);
}

// ---- malformed files ----

const char* kTinyMask = R"(# VERTEX LIST:
4
0 0 0
1 0 0
0 1 0
0 0 1

# FACE LIST:
2
0 1 2
0 2 3

# ANIMATION UNITS LIST:
1

# Jaw drop
2
1 0 -0.1 0
1 0 -0.1 0

# SHAPE UNITS LIST:
1

# Head height
1
2 0 0.2 0

# ANIMATION PARAMETERS:
0.5

# SHAPE PARAMETERS:
0

# TEXTURE:
0 0
1 0
0 1
1 1

# END OF FILE
)";

TEST(Candide3ImportValidity, AMinimalFileParses) {
  auto model = importers::parseCandide3(kTinyMask, "tiny.wfm");
  ASSERT_TRUE(model) << model.error().message;
  // No 'Eyes closed' unit, so no lid margins: said once, and the mask stays whole, with no eyeball.
  ASSERT_EQ(model->warnings.size(), 1u);
  EXPECT_EQ(model->warnings[0].rfind("tiny.wfm: 0 of 2 eye openings found", 0), 0u) << model->warnings[0];
  EXPECT_EQ(model->meshes[0].primitives.size(), 1u);
  EXPECT_EQ(model->meshes[0].primitives[0].indices.size(), 6u);
  const eng::Mesh& mesh = model->meshes[0];
  EXPECT_EQ(mesh.targetNames, (std::vector<std::string>{"AU26 Jaw drop", "SU_Head height"}));
  EXPECT_EQ(mesh.defaultWeights, (std::vector<float>{0.5f, 0.0f}));
  EXPECT_FLOAT_EQ(mesh.primitives[0].targets[0].positions[1].y, -0.2f);
}

std::string errorFor(std::string text) {
  auto model = importers::parseCandide3(text, "mask.wfm");
  return model ? std::string("(accepted)") : model.error().message;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Candide3ImportValidity, ErrorsNameFileLineAndProblem) {
  EXPECT_EQ(errorFor(replaced(kTinyMask, "1 0 0\n", "1 zero 0\n")),
            "mask.wfm:4: expected three finite numbers 'x y z' for vertex 1 of 4, got '1 zero 0'");
  EXPECT_EQ(errorFor(replaced(kTinyMask, "0 2 3\n", "0 2 9\n")),
            "mask.wfm:11: vertex index 9 out of range (4 vertices) in triangle 1 of 2");
  EXPECT_EQ(errorFor(replaced(kTinyMask, "# FACE LIST:", "# FACES:")),
            "mask.wfm:8: expected '# FACE LIST:', got '# FACES:'");
  EXPECT_EQ(errorFor(replaced(kTinyMask, "1 0 -0.1 0\n1 0", "7 0 -0.1 0\n1 0")),
            "mask.wfm:18: vertex index 7 out of range (4 vertices) in 'Jaw drop'");
  EXPECT_EQ(errorFor(replaced(kTinyMask, "0 0 0\n1 0 0", "0 0 nan\n1 0 0")).substr(0, 12), "mask.wfm:3: ");
  EXPECT_NE(errorFor(replaced(kTinyMask, "# ANIMATION UNITS LIST:\n1", "# ANIMATION UNITS LIST:\n2")).find(
                "expected the name line '# <name>' of animation unit 1 of 2, got '# SHAPE UNITS LIST:'"),
            std::string::npos);
  EXPECT_NE(errorFor(replaced(kTinyMask, "# VERTEX LIST:\n4", "# VERTEX LIST:\n99999999999")).find(
                "exceeds the limit"),
            std::string::npos);
  EXPECT_NE(errorFor("# VERTEX LIST:\n4\n0 0 0\n").find("mask.wfm:3: file ends before vertex 1 of 4"),
            std::string::npos);
  EXPECT_NE(errorFor(replaced(kTinyMask, "0 1\n1 1\n", "0 1\n")).find("TEXTURE (u v per vertex) lists 6 values, expected 8"),
            std::string::npos);
  EXPECT_NE(errorFor(replaced(kTinyMask, "# END OF FILE", "trailing junk")).find("unexpected line 'trailing junk'"),
            std::string::npos);
}

TEST(Candide3ImportValidity, MissingFileNamesIt) {
  auto model = importers::importCandide3(testing_support::freshTempDir("candide") / "nope.wfm");
  ASSERT_FALSE(model);
  EXPECT_NE(model.error().message.find("nope.wfm: file not found"), std::string::npos) << model.error().message;
}

}  // namespace
}  // namespace facial
