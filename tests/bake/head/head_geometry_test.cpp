// The built-in head's geometry: size and orientation, vertex budget, a
// closed and consistently oriented skin (with the mouth pocket sewn to the
// lip seam), closed separate parts, and the lip seam being a real split.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <tuple>
#include <unordered_map>

#include "tests/bake/head/built_in_head.h"

namespace {

using bake::HeadPrimitive;
using head_testing::builtInHead;
using head_testing::headMesh;
using head_testing::headPrimitive;

// Vertex ids shared by identical positions (bitwise), across several arrays.
class Welder {
 public:
  uint32_t id(const glm::vec3& p) {
    std::tuple<uint32_t, uint32_t, uint32_t> key;
    const glm::vec3 q = p + glm::vec3(0.0f);  // -0 == +0
    std::memcpy(&std::get<0>(key), &q.x, 4);
    std::memcpy(&std::get<1>(key), &q.y, 4);
    std::memcpy(&std::get<2>(key), &q.z, 4);
    return ids_.try_emplace(key, static_cast<uint32_t>(ids_.size())).first->second;
  }

 private:
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, uint32_t> ids_;
};

struct EdgeReport {
  size_t triangles = 0;
  size_t degenerate = 0;
  size_t unmatched = 0;   // directed edges without exactly one reverse twin
  size_t duplicated = 0;  // directed edges used more than once
  double signedVolume = 0.0;
};

// Every directed edge must appear once and its reverse once: closed, manifold
// along edges, consistently oriented.
EdgeReport checkClosed(const std::vector<std::pair<const std::vector<glm::vec3>*, const std::vector<uint32_t>*>>& parts) {
  Welder welder;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  EdgeReport r;
  for (const auto& [positions, indices] : parts) {
    for (size_t t = 0; t + 2 < indices->size(); t += 3) {
      const glm::vec3 &a = (*positions)[(*indices)[t]], &b = (*positions)[(*indices)[t + 1]],
                      &c = (*positions)[(*indices)[t + 2]];
      const uint32_t ia = welder.id(a), ib = welder.id(b), ic = welder.id(c);
      ++r.triangles;
      if (ia == ib || ib == ic || ia == ic) {
        ++r.degenerate;
        continue;
      }
      ++directed[{ia, ib}];
      ++directed[{ib, ic}];
      ++directed[{ic, ia}];
      r.signedVolume += glm::dot(glm::dvec3(a), glm::cross(glm::dvec3(b), glm::dvec3(c))) / 6.0;
    }
  }
  for (const auto& [edge, count] : directed) {
    if (count > 1) ++r.duplicated;
    auto twin = directed.find({edge.second, edge.first});
    if (twin == directed.end() || twin->second != 1) ++r.unmatched;
  }
  return r;
}

TEST(HeadGeometry, HasEnoughVerticesInTheSkin) {
  const eng::Primitive& skin = headPrimitive(builtInHead().model, HeadPrimitive::Skin);
  EXPECT_GE(skin.vertexCount(), 20000u);
  EXPECT_GE(builtInHead().model.totalVertexCount(), 30000u);
}

TEST(HeadGeometry, IsHeadSizedUprightAndFacesPlusZ) {
  const eng::Model& model = builtInHead().model;
  const eng::Aabb box = model.bounds();
  ASSERT_TRUE(box.valid());
  // An adult head (about 0.22 m crown to chin) and its neck.
  EXPECT_GE(box.size().y, 0.20f);
  EXPECT_LE(box.size().y, 0.32f);
  EXPECT_LT(box.size().x, box.size().y);
  // Centred: symmetric in x, origin inside the head.
  EXPECT_NEAR(box.min.x, -box.max.x, 1e-4f);
  EXPECT_LT(box.min.y, 0.0f);
  EXPECT_GT(box.max.y, 0.0f);
  // The nose tip is the front-most skin point, on the midline, below the eyes.
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  size_t front = 0;
  for (size_t v = 0; v < skin.vertexCount(); ++v)
    if (skin.positions[v].z > skin.positions[front].z) front = v;
  EXPECT_NEAR(skin.positions[front].x, 0.0f, 0.002f);
  EXPECT_LT(skin.positions[front].y, head_testing::landmark(builtInHead(), "lid_upper_L").y);
  EXPECT_GT(skin.positions[front].y, head_testing::landmark(builtInHead(), "upper_lip_centre").y);
}

TEST(HeadGeometry, SkinAndMouthPocketFormOneClosedSurface) {
  // Lips parted so the two sides of the seam are apart; the texture seam at
  // the back and the pocket's border still weld to the skin by position.
  const eng::Model& model = builtInHead().model;
  const int part = head_testing::targetIndex(headMesh(model), "AU25_LipsPart");
  ASSERT_GE(part, 0);
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  const eng::Primitive& mouth = headPrimitive(model, HeadPrimitive::Mouth);
  const std::vector<glm::vec3> skinOpen = head_testing::morphed(skin, part, 1.0f);
  const std::vector<glm::vec3> mouthOpen = head_testing::morphed(mouth, part, 1.0f);
  const EdgeReport r = checkClosed({{&skinOpen, &skin.indices}, {&mouthOpen, &mouth.indices}});
  EXPECT_EQ(r.degenerate, 0u);
  EXPECT_EQ(r.duplicated, 0u);
  EXPECT_EQ(r.unmatched, 0u);
  // Outward-facing, and about the volume of a head and neck (litres).
  EXPECT_GT(r.signedVolume, 0.0015);
  EXPECT_LT(r.signedVolume, 0.0060);
}

TEST(HeadGeometry, SkinAloneIsOpenOnlyAlongTheLipSeam) {
  // Without the pocket, the only boundary is the mouth slit: edges on it lie
  // between the lip corners, at the seam.
  const eng::Model& model = builtInHead().model;
  const int part = head_testing::targetIndex(headMesh(model), "AU25_LipsPart");
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  const std::vector<glm::vec3> open = head_testing::morphed(skin, part, 1.0f);
  Welder welder;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::vector<glm::vec3> atId;
  for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
    uint32_t id[3];
    for (int k = 0; k < 3; ++k) {
      id[k] = welder.id(open[skin.indices[t + k]]);
      if (id[k] >= atId.size()) atId.resize(id[k] + 1);
      atId[id[k]] = skin.positions[skin.indices[t + k]];
    }
    for (int k = 0; k < 3; ++k) ++directed[{id[k], id[(k + 1) % 3]}];
  }
  const glm::vec3 cornerL = head_testing::landmark(builtInHead(), "mouth_corner_L");
  size_t boundary = 0;
  for (const auto& [edge, count] : directed) {
    if (directed.count({edge.second, edge.first})) continue;
    ++boundary;
    for (uint32_t end : {edge.first, edge.second}) {
      const glm::vec3& p = atId[end];
      EXPECT_LE(std::abs(p.x), cornerL.x + 1e-4f) << "boundary outside the mouth at " << p.x << ", " << p.y;
      EXPECT_NEAR(p.y, cornerL.y, 0.006f) << "boundary away from the lip line";
    }
  }
  EXPECT_GT(boundary, 20u);
}

TEST(HeadGeometry, LipSeamIsSplitWithCoincidentSidesAtRest) {
  // At rest the upper and lower lip meet: vertex pairs at identical
  // positions that the lips-part target pulls apart.
  const eng::Model& model = builtInHead().model;
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  const int part = head_testing::targetIndex(headMesh(model), "AU25_LipsPart");
  std::unordered_map<uint64_t, std::vector<size_t>> byPosition;
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    const glm::vec3& p = skin.positions[v];
    if (std::abs(p.y - head_testing::landmark(builtInHead(), "mouth_corner_L").y) > 0.006f || p.z < 0.06f) continue;
    uint64_t key = 0;
    std::memcpy(&key, &p.x, 4);
    uint32_t y = 0;
    std::memcpy(&y, &p.y, 4);
    key = (key << 32) ^ y;
    byPosition[key].push_back(v);
  }
  size_t pairs = 0;
  for (const auto& [key, verts] : byPosition) {
    if (verts.size() != 2) continue;
    const glm::vec3 d0 = skin.targets[part].positions[verts[0]], d1 = skin.targets[part].positions[verts[1]];
    if (glm::length(d0 - d1) > 0.002f) ++pairs;
  }
  EXPECT_GE(pairs, 16u);
}

TEST(HeadGeometry, PartsAreClosedSeparateMeshes) {
  const eng::Model& model = builtInHead().model;
  for (HeadPrimitive p : {HeadPrimitive::TeethUpper, HeadPrimitive::TeethLower, HeadPrimitive::Tongue}) {
    const eng::Primitive& prim = headPrimitive(model, p);
    const EdgeReport r = checkClosed({{&prim.positions, &prim.indices}});
    EXPECT_EQ(r.unmatched, 0u) << "head primitive " << int(p);
    EXPECT_GT(r.signedVolume, 0.0) << "head primitive " << int(p);
  }
  for (const eng::Mesh& mesh : model.meshes) {
    if (mesh.name != "EyeLeft" && mesh.name != "EyeRight" && mesh.name != "Ears") continue;
    EXPECT_TRUE(mesh.targetNames.empty()) << mesh.name;
    ASSERT_EQ(mesh.primitives.size(), mesh.name == "Ears" ? 2u : 1u) << mesh.name;
    for (const eng::Primitive& prim : mesh.primitives) {
      const EdgeReport r = checkClosed({{&prim.positions, &prim.indices}});
      EXPECT_EQ(r.unmatched, 0u) << mesh.name;
      EXPECT_GT(r.signedVolume, 0.0) << mesh.name;
    }
  }
}

TEST(HeadGeometry, EyesSitInTheSocketsBehindTheLidEdges) {
  const bake::GeneratedHead& head = builtInHead();
  for (const char* side : {"L", "R"}) {
    const glm::vec3 upper = head_testing::landmark(head, std::string("lid_upper_") + side);
    const glm::vec3 lower = head_testing::landmark(head, std::string("lid_lower_") + side);
    EXPECT_GT(upper.y - lower.y, 0.008f) << side << ": the eye is open at rest";
    // At rest the eyeball is what a ray through the middle of the opening meets.
    const eng::Primitive eye = head_testing::eyeballInHeadSpace(head.model, side[0] == 'L' ? 0 : 1);
    const glm::vec2 mid((upper.x + lower.x) * 0.5f, (upper.y + lower.y) * 0.5f);
    const auto eyeZ = head_testing::frontHitZ(eye.positions, eye.indices, mid.x, mid.y);
    const eng::Primitive& skin = headPrimitive(head.model, HeadPrimitive::Skin);
    const auto skinZ = head_testing::frontHitZ(skin.positions, skin.indices, mid.x, mid.y);
    ASSERT_TRUE(eyeZ.has_value());
    ASSERT_TRUE(skinZ.has_value());
    EXPECT_GT(*eyeZ, *skinZ) << side;
  }
}

TEST(HeadGeometry, EachEyeballHangsOnANodeAtItsCentre) {
  // The node is the eye's joint: a gaze turns it, and the ball must turn in
  // place rather than swing out of its socket.
  const eng::Model& model = builtInHead().model;
  for (int e = 0; e < 2; ++e) {
    const std::string name = e == 0 ? "EyeLeft" : "EyeRight";
    const auto node = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const eng::Node& n) { return n.name == name; });
    ASSERT_NE(node, model.nodes.end()) << name;
    const head_testing::Eyeball ball = head_testing::eyeball(model, e);
    EXPECT_LT(glm::length(node->translation - ball.centre), 2e-5f) << name;
    EXPECT_GT(node->translation.x * (e == 0 ? 1.0f : -1.0f), 0.0f) << name << " is on the face's own side";
  }
}

}  // namespace
