#include "tests/engine/scene/skin_test_files.h"

#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace scene_test {
namespace {

// Four influences per vertex as the spec's component types.
int addJoints(GltfFileBuilder& b, const std::vector<glm::uvec4>& joints, int type) {
  std::vector<uint8_t> bytes;
  for (const glm::uvec4& j : joints)
    for (int i = 0; i < 4; ++i) {
      if (type == kUnsignedByte) {
        bytes.push_back(uint8_t(j[i]));
      } else {
        const uint16_t v = uint16_t(j[i]);
        bytes.push_back(uint8_t(v & 0xFF));
        bytes.push_back(uint8_t(v >> 8));
      }
    }
  return b.addAccessor(b.addView(bytes.data(), bytes.size()), type, joints.size(), "VEC4");
}

int addWeights(GltfFileBuilder& b, const std::vector<glm::vec4>& weights, int type) {
  if (type == kFloat) return b.addAccessor(b.addView(weights), kFloat, weights.size(), "VEC4");
  std::vector<uint8_t> bytes;
  for (const glm::vec4& w : weights)
    for (int i = 0; i < 4; ++i) {
      if (type == kUnsignedByte) {
        bytes.push_back(uint8_t(std::lround(w[i] * 255.0f)));
      } else {
        const uint16_t v = uint16_t(std::lround(w[i] * 65535.0f));
        bytes.push_back(uint8_t(v & 0xFF));
        bytes.push_back(uint8_t(v >> 8));
      }
    }
  return b.addAccessor(b.addView(bytes.data(), bytes.size()), type, weights.size(), "VEC4", /*normalized=*/true);
}

}  // namespace

GltfFileBuilder skinnedStrip(const SkinnedStripSpec& spec) {
  GltfFileBuilder b;
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  const std::vector<glm::vec3> normals(6, glm::vec3(0, 0, 1));
  const int pos = b.addVec3(positions, true);
  const int nrm = b.addVec3(normals);
  const int idx = b.addIndices({0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3});
  std::vector<glm::uvec4> joints(6, glm::uvec4(0, 1, 0, 0));
  std::vector<glm::vec4> weights = {{1, 0, 0, 0}, {1, 0, 0, 0}, {0.5f, 0.5f, 0, 0},
                                    {0.5f, 0.5f, 0, 0}, {0, 1, 0, 0}, {0, 1, 0, 0}};
  Json attributes = {{"POSITION", pos}, {"NORMAL", nrm}};
  if (spec.secondInfluenceSet) {
    // Half of each weight in each set: the loader must sum both.
    for (glm::vec4& w : weights) w *= 0.5f;
    attributes["JOINTS_1"] = addJoints(b, joints, spec.jointType);
    attributes["WEIGHTS_1"] = addWeights(b, weights, spec.weightType);
  }
  attributes["JOINTS_0"] = addJoints(b, joints, spec.jointType);
  attributes["WEIGHTS_0"] = addWeights(b, weights, spec.weightType);
  b.addMeshWithNode({{"name", "Strip"}, {"primitives", Json::array({{{"attributes", attributes}, {"indices", idx}}})}});

  const glm::mat4 inverseBind[2] = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0))};
  const int ibm = b.addAccessor(b.addView(inverseBind, sizeof(inverseBind)), kFloat, 2, "MAT4");
  b.doc["nodes"][0]["skin"] = 0;
  b.doc["nodes"].push_back({{"name", "Hips"}, {"children", {2}}});
  b.doc["nodes"].push_back({{"name", "Head"}, {"translation", {1.0, 0.0, 0.0}}});
  b.doc["scenes"][0]["nodes"].push_back(1);
  b.doc["skins"] = Json::array({{{"name", "Armature"}, {"joints", {1, 2}}, {"inverseBindMatrices", ibm}, {"skeleton", 1}}});

  const glm::quat turned = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  const int times = b.addScalars({0.0f, 1.0f});
  std::vector<float> rotations;
  if (spec.interpolation == "CUBICSPLINE") {
    // in-tangent, value, out-tangent per key; zero tangents.
    rotations = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, turned.x, turned.y, turned.z, turned.w, 0, 0, 0, 0};
  } else {
    rotations = {0, 0, 0, 1, turned.x, turned.y, turned.z, turned.w};
  }
  const int values = b.addAccessor(b.addView(rotations), kFloat, rotations.size() / 4, "VEC4");
  b.doc["animations"] = Json::array(
      {{{"name", "bend"},
        {"samplers", Json::array({{{"input", times}, {"output", values}, {"interpolation", spec.interpolation}}})},
        {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}})}}});
  return b;
}

}  // namespace scene_test
