// A Ready Player Me-like avatar, built by the test (../shared has none): a
// full-body skinned figure (Hips > Spine > Neck > Head) whose head is one
// mesh split over three primitives (skin, teeth, eyes) carrying Apple's 52
// ARKit blend shapes, beside a body mesh. It must load, be rigged as ARKit,
// frame its face with --frame face (the default) rather than the whole
// figure, and each of the seven expression presets must move the face.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "app/face_setup.h"
#include "engine/scene/gltf_writer.h"
#include "facial/runtime/rig/arkit_names.h"
#include "tests/cli/cli_runner.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

namespace cli_test {
namespace {

enum Joint : uint16_t { kHips, kSpine, kNeck, kHead, kJoints };
constexpr float kHeadCentreY = 1.72f;
constexpr float kHeadRadius = 0.11f;

// A UV sphere (or a squashed one) skinned fully to `joint`.
eng::Primitive sphere(glm::vec3 centre, glm::vec3 radii, int rings, int segments, uint16_t joint, int material) {
  eng::Primitive p;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = glm::pi<float>() * float(r) / float(rings);
      const float phi = 2.0f * glm::pi<float>() * float(s) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
      p.positions.push_back(centre + radii * n);
      p.normals.push_back(n);
      p.joints.push_back({joint, 0, 0, 0});
      p.jointWeights.push_back({1.0f, 0.0f, 0.0f, 0.0f});
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t i = uint32_t(r * (segments + 1) + s), below = i + uint32_t(segments + 1);
      p.indices.insert(p.indices.end(), {i, below, i + 1, i + 1, below, below + 1});
    }
  p.material = material;
  return p;
}

// Target k of the 52 moves the front of the face around its own spot (a
// ring of spots over the face), teeth follow jawOpen and the eyes close
// with the blinks: every primitive carries all 52 targets, as glTF requires.
void addArkitTargets(eng::Mesh& head) {
  const auto names = facial::arkitBlendShapeNames();
  head.targetNames.assign(names.begin(), names.end());
  head.defaultWeights.assign(names.size(), 0.0f);
  for (size_t prim = 0; prim < head.primitives.size(); ++prim) {
    eng::Primitive& p = head.primitives[prim];
    for (size_t k = 0; k < names.size(); ++k) {
      eng::MorphTarget t;
      const float angle = 2.0f * glm::pi<float>() * float(k) / float(names.size());
      const glm::vec3 spot(0.06f * std::cos(angle), kHeadCentreY + 0.06f * std::sin(angle), kHeadRadius);
      for (const glm::vec3& v : p.positions) {
        glm::vec3 d(0.0f);
        if (prim == 0 && v.z > 0.0f) {
          const float falloff = std::exp(-glm::dot(v - spot, v - spot) / (0.035f * 0.035f));
          d = falloff * glm::vec3(0.0f, 0.012f * std::sin(3.0f * angle), 0.02f);
        } else if (prim == 1 && names[k] == "jawOpen") {
          d = glm::vec3(0.0f, -0.02f, 0.0f);
        } else if (prim == 2 && names[k].starts_with("eyeBlink")) {
          d = glm::vec3(0.0f, 0.5f * (kHeadCentreY + 0.03f - v.y), 0.0f);
        }
        t.positions.push_back(d);
      }
      p.targets.push_back(std::move(t));
    }
  }
}

eng::Model makeFullBodyAvatar() {
  eng::Model model;
  for (const char* name : {"skin", "teeth", "eyes", "outfit"}) model.materials.emplace_back().name = name;
  model.materials[0].baseColorFactor = {0.85f, 0.62f, 0.5f, 1.0f};
  model.materials[1].baseColorFactor = {0.95f, 0.95f, 0.9f, 1.0f};
  model.materials[2].baseColorFactor = {0.1f, 0.1f, 0.12f, 1.0f};
  model.materials[3].baseColorFactor = {0.15f, 0.25f, 0.7f, 1.0f};

  eng::Mesh head;
  head.name = "Wolf3D_Head";
  head.primitives.push_back(sphere({0.0f, kHeadCentreY, 0.0f}, glm::vec3(kHeadRadius), 16, 24, kHead, 0));
  head.primitives.push_back(sphere({0.0f, kHeadCentreY - 0.05f, 0.08f}, {0.03f, 0.01f, 0.02f}, 4, 8, kHead, 1));
  eng::Primitive eyes = sphere({-0.04f, kHeadCentreY + 0.03f, 0.095f}, glm::vec3(0.016f), 6, 8, kHead, 2);
  const eng::Primitive right = sphere({0.04f, kHeadCentreY + 0.03f, 0.095f}, glm::vec3(0.016f), 6, 8, kHead, 2);
  const uint32_t base = uint32_t(eyes.positions.size());
  eyes.positions.insert(eyes.positions.end(), right.positions.begin(), right.positions.end());
  eyes.normals.insert(eyes.normals.end(), right.normals.begin(), right.normals.end());
  eyes.joints.insert(eyes.joints.end(), right.joints.begin(), right.joints.end());
  eyes.jointWeights.insert(eyes.jointWeights.end(), right.jointWeights.begin(), right.jointWeights.end());
  for (uint32_t i : right.indices) eyes.indices.push_back(base + i);
  head.primitives.push_back(std::move(eyes));
  addArkitTargets(head);

  // Torso and legs: a tall ellipsoid on the hips and spine, neck on the neck joint.
  eng::Mesh body;
  body.name = "Wolf3D_Body";
  eng::Primitive torso = sphere({0.0f, 1.05f, 0.0f}, {0.22f, 0.52f, 0.13f}, 16, 16, kSpine, 3);
  for (size_t v = 0; v < torso.positions.size(); ++v)
    if (torso.positions[v].y < 1.0f) torso.joints[v].x = kHips;
  body.primitives.push_back(std::move(torso));
  body.primitives.push_back(sphere({0.0f, 1.6f, 0.0f}, {0.05f, 0.08f, 0.05f}, 6, 8, kNeck, 0));
  body.primitives.push_back(sphere({0.0f, 0.45f, 0.0f}, {0.16f, 0.45f, 0.1f}, 8, 8, kHips, 3));
  model.meshes = {std::move(head), std::move(body)};

  // Armature > Hips > Spine > Neck > Head; the mesh nodes beside the hips, as Ready Player Me exports them.
  const std::array<std::pair<const char*, float>, kJoints> joints{
      {{"Hips", 1.0f}, {"Spine", 1.3f}, {"Neck", 1.55f}, {"Head", 1.65f}}};
  model.nodes.emplace_back().name = "Armature";
  eng::Skin skin;
  skin.name = "avatar";
  float parentY = 0.0f;
  for (size_t j = 0; j < joints.size(); ++j) {
    eng::Node node;
    node.name = joints[j].first;
    node.translation = {0.0f, joints[j].second - parentY, 0.0f};
    node.parent = int(j);  // the armature, then the previous joint
    parentY = joints[j].second;
    model.nodes[size_t(node.parent)].children.push_back(int(model.nodes.size()));
    skin.joints.push_back(int(model.nodes.size()));
    skin.inverseBindMatrices.push_back(glm::translate(glm::mat4(1.0f), {0.0f, -joints[j].second, 0.0f}));
    model.nodes.push_back(std::move(node));
  }
  skin.skeleton = 1;
  model.skins.push_back(std::move(skin));
  for (int m = 0; m < 2; ++m) {
    eng::Node node;
    node.name = model.meshes[size_t(m)].name;
    node.mesh = m;
    node.skin = 0;
    node.parent = 0;
    model.nodes[0].children.push_back(int(model.nodes.size()));
    model.nodes.push_back(std::move(node));
  }
  model.roots = {0};
  return model;
}

std::filesystem::path writeAvatar(const std::string& name) {
  const std::filesystem::path path = testing_support::freshTempDir(name) / "avatar.glb";
  if (auto saved = eng::saveModel(makeFullBodyAvatar(), path); !saved)
    ADD_FAILURE() << "cannot write the avatar: " << saved.error().message;
  return path;
}

// Pixels of the skin colour (the head and neck): red well above blue.
size_t skinPixels(const eng::Image& image) {
  size_t n = 0;
  for (size_t p = 0; p < image.rgba8.size(); p += 4)
    n += image.rgba8[p + 3] > 0 && int(image.rgba8[p]) > int(image.rgba8[p + 2]) + 40 ? 1 : 0;
  return n;
}

TEST(FullBodyAvatar, LoadsAsAnArkitRigAndEveryPresetMovesTheFaceTargets) {
  const std::filesystem::path avatar = writeAvatar("full_body_avatar_rig");
  const CommandOutput rig = runFacial({"rig", avatar.string()});
  ASSERT_EQ(rig.exitCode, 0) << rig.err;
  EXPECT_NE(rig.out.find("ARKit"), std::string::npos) << rig.out;

  auto face = app::FaceSetup::load({.model = avatar});
  ASSERT_TRUE(face) << face.error().message;
  EXPECT_EQ(face->rig().scheme(), facial::RigScheme::Arkit52);
  ASSERT_EQ(face->model().meshes[0].primitives.size(), 3u);
  std::vector<float> weights(face->weightCount());
  for (const char* name : {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"}) {
    auto preset = face->findExpression(name);
    ASSERT_TRUE(preset) << preset.error().message;
    ASSERT_TRUE(face->expressionWeights(**preset, 1.0f, weights));
    const float strongest = *std::max_element(weights.begin(), weights.end());
    if (std::string(name) == "neutral")
      EXPECT_EQ(strongest, 0.0f) << "neutral is the rest face";
    else
      EXPECT_GT(strongest, 0.2f) << name << " drives no ARKit target";
  }
}

TEST(FullBodyAvatar, FramesItsFaceAndEachPresetChangesTheFaceOnScreen) {
  const std::filesystem::path avatar = writeAvatar("full_body_avatar_frames");
  const std::filesystem::path dir = avatar.parent_path();
  auto express = [&](const std::string& expression, const std::string& frame) {
    const std::filesystem::path png = dir / (expression + "_" + frame + ".png");
    EXPECT_TRUE(ranCleanly(runFacial({"express", expression, "--model", avatar.string(), "--frame", frame, "--size",
                                      "96x96", "--background", "transparent", "--out", png.string()})));
    return readPngOrFail(png);
  };
  const eng::Image faceFramed = express("neutral", "face");
  const eng::Image wholeBody = express("neutral", "all");
  ASSERT_FALSE(faceFramed.rgba8.empty() || wholeBody.rgba8.empty());
  EXPECT_GT(skinPixels(faceFramed), 96u * 96u / 5) << "the head fills the face framing";
  EXPECT_GT(skinPixels(faceFramed), 6 * skinPixels(wholeBody)) << "and is a small part of the whole figure";
  for (const char* name : {"happy", "sad", "anger", "fear", "surprise", "disgust"})
    EXPECT_GT(differingFraction(faceFramed, express(name, "face"), 8), 0.01) << name << " leaves the face as it was";
}

}  // namespace
}  // namespace cli_test
