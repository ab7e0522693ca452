// The built-in head as a character: mirror-symmetric down to every vertex,
// and a mouth that holds together in every action-unit pose (teeth and
// tongue stay inside the lips and the mouth pocket; the lips never cross at
// the seam).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "facial/runtime/rig/action_units.h"
#include "tests/facial_head/built_in_head.h"

namespace {

using facial::HeadPrimitive;
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
    if (mesh.name != "Eyes" && mesh.name != "Ears") continue;
    ASSERT_EQ(mesh.primitives.size(), 2u) << mesh.name;
    EXPECT_LT(worstMirrorGap(mesh.primitives[0].positions, mesh.primitives[1].positions), kTolerance) << mesh.name;
  }
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

// Triangles of the closed skin + mouth pocket surface, as corner positions.
struct Triangle {
  glm::vec3 a, b, c;
};

bool rayHits(const glm::vec3& origin, const glm::vec3& dir, const Triangle& t) {
  // Moller-Trumbore, hits in front of the origin only.
  const glm::vec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const glm::vec3 pv = glm::cross(dir, e2);
  const float det = glm::dot(e1, pv);
  if (std::abs(det) < 1e-14f) return false;
  const glm::vec3 tv = origin - t.a;
  const float u = glm::dot(tv, pv) / det;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(dir, qv) / det;
  if (v < 0.0f || u + v > 1.0f) return false;
  return glm::dot(e2, qv) / det > 0.0f;
}

TEST(HeadShape, TeethAndTongueStayInsideTheMouthInEveryPose) {
  // The skin and the mouth pocket form one closed surface in every pose; a
  // tooth or tongue vertex is inside it when a ray from it crosses it an odd
  // number of times. A tooth poking through a lip would be outside.
  const eng::Model& model = builtInHead().model;
  const eng::Primitive& skin = headPrimitive(model, HeadPrimitive::Skin);
  const eng::Primitive& mouth = headPrimitive(model, HeadPrimitive::Mouth);
  const glm::vec3 dir = glm::normalize(glm::vec3(0.00037f, 0.00061f, 1.0f));  // off any axis-aligned edge
  for (const auto& pose : mouthPoses()) {
    const std::vector<glm::vec3> skinPosed = posed(skin, pose), mouthPosed = posed(mouth, pose);
    // Only triangles in front of the mouth can be crossed by the forward rays.
    std::vector<Triangle> front;
    auto collect = [&](const std::vector<glm::vec3>& p, const std::vector<uint32_t>& idx) {
      for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        const Triangle tri{p[idx[t]], p[idx[t + 1]], p[idx[t + 2]]};
        const float maxZ = std::max({tri.a.z, tri.b.z, tri.c.z});
        const float minY = std::min({tri.a.y, tri.b.y, tri.c.y}), maxY = std::max({tri.a.y, tri.b.y, tri.c.y});
        const float minX = std::min({tri.a.x, tri.b.x, tri.c.x}), maxX = std::max({tri.a.x, tri.b.x, tri.c.x});
        if (maxZ > 0.03f && maxY > -0.11f && minY < -0.02f && minX < 0.04f && maxX > -0.04f) front.push_back(tri);
      }
    };
    collect(skinPosed, skin.indices);
    collect(mouthPosed, mouth.indices);
    for (HeadPrimitive part : {HeadPrimitive::TeethUpper, HeadPrimitive::TeethLower, HeadPrimitive::Tongue}) {
      const eng::Primitive& prim = headPrimitive(model, part);
      const std::vector<glm::vec3> p = posed(prim, pose);
      size_t outside = 0;
      std::optional<glm::vec3> example;
      for (size_t v = 0; v < p.size(); v += 2) {
        int crossings = 0;
        for (const Triangle& t : front) crossings += rayHits(p[v], dir, t) ? 1 : 0;
        if (crossings % 2 == 0) {
          ++outside;
          if (!example) example = p[v];
        }
      }
      EXPECT_EQ(outside, 0u) << describe(pose) << ": " << outside << " vertices of head primitive " << int(part)
                             << " outside the lips, e.g. at (" << example.value_or(glm::vec3(0)).x << ", "
                             << example.value_or(glm::vec3(0)).y << ", " << example.value_or(glm::vec3(0)).z << ")";
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
