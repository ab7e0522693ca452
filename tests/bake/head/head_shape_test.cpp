// The built-in head as a character: mirror-symmetric down to every vertex,
// and a mouth that holds together in every action-unit pose (teeth and
// tongue stay behind the lips; the lips never cross at the seam).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "facial/runtime/rig/action_units.h"
#include "tests/bake/head/built_in_head.h"

namespace {

using bake::HeadPrimitive;
using head_testing::builtInHead;
using head_testing::headMesh;
using head_testing::headPrimitive;
using head_testing::targetIndex;

// Largest distance from a vertex of `a`, mirrored (x -> -x), to the nearest vertex of `b`.
float worstMirrorGap(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  // Bucket b on a 2 mm grid; a mirror twin further than that counts as 2 mm.
  constexpr float kCell = 0.002f;
  std::map<std::tuple<int, int, int>, std::vector<size_t>> cells;
  auto cellOf = [](const glm::vec3& p) {
    return std::make_tuple(int(std::floor(p.x / kCell)), int(std::floor(p.y / kCell)), int(std::floor(p.z / kCell)));
  };
  for (size_t i = 0; i < b.size(); ++i) cells[cellOf(b[i])].push_back(i);
  float worst = 0.0f;
  for (const glm::vec3& p : a) {
    const glm::vec3 m(-p.x, p.y, p.z);
    const auto [cx, cy, cz] = cellOf(m);
    float best = kCell;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells.find({cx + dx, cy + dy, cz + dz});
          if (it == cells.end()) continue;
          for (size_t i : it->second) best = std::min(best, glm::length(b[i] - m));
        }
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(HeadShape, EveryVertexHasAMirrorTwin) {
  // A tenth of a millimetre: far below a pixel on any screen-filling face.
  constexpr float kTolerance = 1e-4f;
  const eng::Model& model = builtInHead().model;
  for (const eng::Primitive& prim : headMesh(model).primitives)
    EXPECT_LT(worstMirrorGap(prim.positions, prim.positions), kTolerance) << "a head primitive is not symmetric";
  for (const eng::Mesh& mesh : model.meshes) {
    if (mesh.name != "Ears") continue;
    ASSERT_EQ(mesh.primitives.size(), 2u) << mesh.name;
    EXPECT_LT(worstMirrorGap(mesh.primitives[0].positions, mesh.primitives[1].positions), kTolerance) << mesh.name;
  }
  EXPECT_LT(worstMirrorGap(head_testing::eyeballInHeadSpace(model, 0).positions, head_testing::eyeballInHeadSpace(model, 1).positions),
            kTolerance)
      << "eyeballs";
}

// Poses to check: every unit at full weight, and the strongest mouth combinations.
std::vector<std::vector<std::pair<std::string, float>>> mouthPoses() {
  std::vector<std::vector<std::pair<std::string, float>>> poses;
  for (const facial::ActionUnitInfo& info : facial::actionUnits()) poses.push_back({{std::string(info.name), 1.0f}});
  poses.push_back({{"AU12_LipCornerPuller_L", 1.0f}, {"AU12_LipCornerPuller_R", 1.0f}, {"AU6_CheekRaiser", 1.0f},
                   {"AU25_LipsPart", 1.0f}});
  poses.push_back({{"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 1.0f}, {"AU20_LipStretcher", 1.0f}});
  poses.push_back({{"AU9_NoseWrinkler", 1.0f}, {"AU10_UpperLipRaiser", 1.0f}, {"AU15_LipCornerDepressor", 1.0f},
                   {"AU17_ChinRaiser", 1.0f}, {"AU25_LipsPart", 1.0f}});
  poses.push_back({{"AU23_LipTightener", 1.0f}, {"AU24_LipPressor", 1.0f}, {"AU17_ChinRaiser", 1.0f}});
  poses.push_back({{"AU15_LipCornerDepressor", 1.0f}, {"AU17_ChinRaiser", 1.0f}, {"AU16_LowerLipDepressor", 1.0f}});
  // The speech units at full weight and as the visemes mix them (O, U, TH, PP, aa).
  poses.push_back({{"AU22_LipFunneler", 1.0f}, {"AU18_LipPucker", 1.0f}, {"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 1.0f}});
  poses.push_back({{"AU18_LipPucker", 1.0f}, {"AU22_LipFunneler", 0.3f}, {"AU25_LipsPart", 0.6f}, {"AU26_JawDrop", 0.3f}});
  poses.push_back({{"AU19_TongueShow", 1.0f}, {"AU25_LipsPart", 0.6f}, {"AU26_JawDrop", 0.15f}});
  poses.push_back({{"AU19_TongueShow", 1.0f}, {"AU26_JawDrop", 1.0f}, {"AU27_MouthStretch", 1.0f}});
  poses.push_back({{"AU24_LipPressor", 1.0f}, {"AU23_LipTightener", 1.0f}, {"AU28_LipSuck", 1.0f}});
  poses.push_back({{"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 1.0f}, {"AU27_MouthStretch", 1.0f}});
  poses.push_back({{"AU29_JawThrust", 1.0f}, {"AU25_LipsPart", 1.0f}, {"AU26_JawDrop", 0.3f}});
  return poses;
}

std::vector<glm::vec3> posed(const eng::Primitive& prim, const std::vector<std::pair<std::string, float>>& pose) {
  std::vector<glm::vec3> out = prim.positions;
  for (const auto& [name, weight] : pose) {
    const int t = targetIndex(headMesh(builtInHead().model), name);
    if (t < 0) throw std::runtime_error("no target " + name);
    for (size_t v = 0; v < out.size(); ++v) out[v] += weight * prim.targets[t].positions[v];
  }
  return out;
}

std::string describe(const std::vector<std::pair<std::string, float>>& pose) {
  std::string s;
  for (const auto& [name, weight] : pose) s += (s.empty() ? "" : " + ") + name;
  return s;
}

TEST(HeadShape, TeethAndTongueStayBehindTheLipsInEveryPose) {
  // Seen from the front, skin lying just behind a tooth or tongue vertex (within
  // 5 mm) means that vertex has come through the lips. Vertices seen through
  // the parted lips have only the far side of the head behind them.
  const eng::Model& model = builtInHead().model;
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  for (const auto& pose : mouthPoses()) {
    const std::vector<glm::vec3> skinPosed = posed(skin, pose);
    // Only skin around the mouth can lie right behind the teeth.
    std::vector<uint32_t> nearMouth;
    for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
      const glm::vec3 &a = skinPosed[skin.indices[t]], &b = skinPosed[skin.indices[t + 1]],
                      &c = skinPosed[skin.indices[t + 2]];
      if (std::max({a.z, b.z, c.z}) > 0.05f && std::max({a.y, b.y, c.y}) > -0.10f && std::min({a.y, b.y, c.y}) < -0.03f)
        nearMouth.insert(nearMouth.end(), {skin.indices[t], skin.indices[t + 1], skin.indices[t + 2]});
    }
    const head_testing::FrontView front(skinPosed, nearMouth);
    for (HeadPrimitive part : {HeadPrimitive::TeethUpper, HeadPrimitive::TeethLower, HeadPrimitive::Tongue}) {
      const std::vector<glm::vec3> p = posed(headPrimitive(model, part), pose);
      size_t through = 0;
      glm::vec3 example(0.0f);
      for (size_t v = 0; v < p.size(); v += 2) {
        const std::optional<float> z = front.hitZ(p[v].x, p[v].y);
        if (z && *z < p[v].z && *z > p[v].z - 0.005f) {
          if (through++ == 0) example = p[v];
        }
      }
      EXPECT_EQ(through, 0u) << describe(pose) << ": " << through << " vertices of head primitive " << int(part)
                             << " in front of the lips, e.g. at (" << example.x << ", " << example.y << ", "
                             << example.z << ")";
    }
  }
}

TEST(HeadShape, LipsNeverCrossAtTheSeam) {
  // The seam's two sides coincide at rest; the side that AU25 lifts is the
  // upper lip. In no pose may it end up below its lower twin.
  const eng::Model& model = builtInHead().model;
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  const int part = targetIndex(headMesh(model), "AU25_LipsPart");
  ASSERT_GE(part, 0);
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, std::vector<size_t>> byPosition;
  for (size_t v = 0; v < skin.vertexCount(); ++v) {
    const glm::vec3 p = skin.positions[v] + glm::vec3(0.0f);
    if (p.z < 0.06f || std::abs(p.y - head_testing::landmark(builtInHead(), "mouth_corner_L").y) > 0.006f) continue;
    std::tuple<uint32_t, uint32_t, uint32_t> key;
    std::memcpy(&std::get<0>(key), &p.x, 4);
    std::memcpy(&std::get<1>(key), &p.y, 4);
    std::memcpy(&std::get<2>(key), &p.z, 4);
    byPosition[key].push_back(v);
  }
  std::vector<std::pair<size_t, size_t>> seam;  // (upper, lower)
  for (const auto& [key, verts] : byPosition) {
    if (verts.size() != 2) continue;
    const float up0 = skin.targets[part].positions[verts[0]].y, up1 = skin.targets[part].positions[verts[1]].y;
    if (std::abs(up0 - up1) < 0.001f) continue;
    seam.emplace_back(up0 > up1 ? verts[0] : verts[1], up0 > up1 ? verts[1] : verts[0]);
  }
  ASSERT_GE(seam.size(), 20u);
  for (const auto& pose : mouthPoses()) {
    const std::vector<glm::vec3> p = posed(skin, pose);
    float worst = 0.0f;
    for (const auto& [upper, lower] : seam) worst = std::max(worst, p[lower].y - p[upper].y);
    EXPECT_LT(worst, 2e-4f) << describe(pose) << ": the lower lip rises " << worst * 1000.0f << " mm over the upper";
  }
}

}  // namespace
