#include "tests/autorig/transfer_fixture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace transfer_fixture {
namespace {

// iBUG-68 in the head's front plane (x: the subject's left, y: up), metres.
// Eyes around the eyeballs at (+-0.0335, 0.009); mouth corners at +-0.024.
constexpr std::array<std::array<float, 2>, 68> kHeadLayout{{
    {-0.068f, 0.005f}, {-0.0672f, -0.0122f}, {-0.0648f, -0.0287f}, {-0.0596f, -0.0437f}, {-0.0481f, -0.0572f},
    {-0.0378f, -0.0669f}, {-0.026f, -0.0753f}, {-0.0133f, -0.0805f}, {0.0f, -0.083f}, {0.0133f, -0.0805f},
    {0.026f, -0.0753f}, {0.0378f, -0.0669f}, {0.0481f, -0.0572f}, {0.0596f, -0.0437f}, {0.0648f, -0.0287f},
    {0.0672f, -0.0122f}, {0.068f, 0.005f},
    {-0.051f, 0.0272f}, {-0.042f, 0.030f}, {-0.031f, 0.0308f}, {-0.021f, 0.029f}, {-0.0125f, 0.0248f},
    {0.0125f, 0.0248f}, {0.021f, 0.029f}, {0.031f, 0.0308f}, {0.042f, 0.030f}, {0.051f, 0.0272f},
    {0.0f, 0.015f}, {0.0f, 0.003f}, {0.0f, -0.009f}, {0.0f, -0.0215f},
    {-0.013f, -0.027f}, {-0.007f, -0.029f}, {0.0f, -0.030f}, {0.007f, -0.029f}, {0.013f, -0.027f},
    {-0.048f, 0.009f}, {-0.039f, 0.0135f}, {-0.028f, 0.0135f}, {-0.019f, 0.009f}, {-0.028f, 0.005f}, {-0.039f, 0.005f},
    {0.019f, 0.009f}, {0.028f, 0.0135f}, {0.039f, 0.0135f}, {0.048f, 0.009f}, {0.039f, 0.005f}, {0.028f, 0.005f},
    {-0.024f, -0.0505f}, {-0.015f, -0.0465f}, {-0.006f, -0.0445f}, {0.0f, -0.0455f}, {0.006f, -0.0445f},
    {0.015f, -0.0465f}, {0.024f, -0.0505f}, {0.015f, -0.055f}, {0.006f, -0.0565f}, {0.0f, -0.057f},
    {-0.006f, -0.0565f}, {-0.015f, -0.055f},
    {-0.021f, -0.0505f}, {-0.008f, -0.0497f}, {0.0f, -0.0497f}, {0.008f, -0.0497f}, {0.021f, -0.0505f},
    {0.008f, -0.0508f}, {0.0f, -0.0508f}, {-0.008f, -0.0508f},
}};

// The frontmost skin hit of the ray from (x, y, +inf) along -Z (barycentrics in the xy plane: the ray is axis-aligned).
std::optional<glm::vec3> castAlongMinusZ(const eng::Model& head, const autorig::PosedFace& posed,
                                         const autorig::FaceParts& parts, float x, float y) {
  std::optional<glm::vec3> best;
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    const autorig::PosedPrimitive& p = posed.primitives[pi];
    const eng::Primitive& primitive = head.meshes[p.mesh].primitives[p.primitive];
    for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
      const uint32_t ia = primitive.indices[i], ib = primitive.indices[i + 1], ic = primitive.indices[i + 2];
      if (parts.vertexParts[pi][ia] != autorig::FacePart::Skin) continue;
      const glm::vec3 &a = p.positions[ia], &b = p.positions[ib], &c = p.positions[ic];
      const float d = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (std::abs(d) < 1e-14f) continue;
      const float u = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / d;
      const float v = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / d;
      if (u < 0.0f || v < 0.0f || u + v > 1.0f) continue;
      const glm::vec3 hit = a + u * (b - a) + v * (c - a);
      if (!best || hit.z > best->z) best = hit;
    }
  }
  return best;
}

}  // namespace

std::optional<eng::Model> loadHead() {
  eng::Result<eng::Model> model = eng::loadModel(testing_support::sourceDir() / "data/head.glb");
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return std::nullopt;
  }
  return std::move(*model);
}

autorig::FaceParts headParts(const eng::Model& head, const autorig::PosedFace& posed) {
  autorig::FaceParts parts;
  std::array<glm::vec3, 2> sum{};
  std::array<size_t, 2> count{};
  for (const autorig::PosedPrimitive& p : posed.primitives) {
    const eng::Mesh& mesh = head.meshes[p.mesh];
    const int material = mesh.primitives[p.primitive].material;
    const std::string name = material >= 0 ? head.materials[size_t(material)].name : "";
    autorig::FacePart part = autorig::FacePart::Other;
    if (name == "Skin" || name == "Ear" || name == "MouthInterior") part = autorig::FacePart::Skin;
    if (name == "Tongue") part = autorig::FacePart::Tongue;
    if (name == "Teeth") part = p.primitive == 2 ? autorig::FacePart::UpperTeeth : autorig::FacePart::LowerTeeth;
    if (mesh.name == "EyeRight") part = autorig::FacePart::EyeballRight;
    if (mesh.name == "EyeLeft") part = autorig::FacePart::EyeballLeft;
    parts.vertexParts.emplace_back(p.positions.size(), part);
    const int eye = part == autorig::FacePart::EyeballRight ? 0 : part == autorig::FacePart::EyeballLeft ? 1 : -1;
    if (eye < 0) continue;
    for (const glm::vec3& v : p.positions) sum[size_t(eye)] += v, ++count[size_t(eye)];
  }
  for (size_t e = 0; e < 2; ++e) {
    if (count[e] == 0) continue;
    parts.eyeCentres[e] = sum[e] / float(count[e]);
    for (const autorig::PosedPrimitive& p : posed.primitives)
      if (head.meshes[p.mesh].name == (e == 0 ? "EyeRight" : "EyeLeft"))
        for (const glm::vec3& v : p.positions)
          parts.eyeRadii[e] = std::max(parts.eyeRadii[e], glm::length(v - parts.eyeCentres[e]));
  }
  parts.eyeballsFound = count[0] > 0 && count[1] > 0;
  return parts;
}

autorig::FaceLandmarks headLandmarks(const eng::Model& head, const autorig::PosedFace& posed,
                                     const autorig::FaceParts& parts) {
  autorig::FaceLandmarks landmarks;
  landmarks.source = "hand-placed on data/head.glb (tests/autorig/transfer_fixture.cpp)";
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const std::optional<glm::vec3> hit = castAlongMinusZ(head, posed, parts, kHeadLayout[i][0], kHeadLayout[i][1]);
    EXPECT_TRUE(hit.has_value()) << "landmark " << i << " misses the head's skin";
    landmarks.points[i] = hit.value_or(glm::vec3(kHeadLayout[i][0], kHeadLayout[i][1], 0.0f));
  }
  return landmarks;
}

autorig::SourceFace headSource(const eng::Model& head) {
  autorig::SourceFace source{.model = &head, .posed = autorig::poseAtRest(head), .landmarks = {}, .parts = {}};
  source.parts = headParts(head, source.posed);
  source.landmarks = headLandmarks(head, source.posed, source.parts);
  return source;
}

float relativeError(const eng::Model& a, const eng::Model& b, const char* mesh, size_t primitive, const char* targetA,
                    const char* targetB) {
  auto find = [&](const eng::Model& model, const char* target) -> std::pair<const eng::Mesh*, size_t> {
    for (const eng::Mesh& m : model.meshes) {
      if (m.name != mesh) continue;
      auto it = std::find(m.targetNames.begin(), m.targetNames.end(), target);
      if (it != m.targetNames.end()) return {&m, size_t(it - m.targetNames.begin())};
    }
    return {nullptr, 0};
  };
  const auto [ma, ta] = find(a, targetA);
  const auto [mb, tb] = find(b, targetB);
  if (!ma || !mb) {
    ADD_FAILURE() << "no target " << (ma ? targetB : targetA) << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  float size = 0.0f, worst = 0.0f;
  if (primitive >= ma->primitives.size() || primitive >= mb->primitives.size()) {
    ADD_FAILURE() << "no primitive " << primitive << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  const std::vector<glm::vec3>& da = ma->primitives[primitive].targets[ta].positions;
  const std::vector<glm::vec3>& db = mb->primitives[primitive].targets[tb].positions;
  for (size_t v = 0; v < da.size() && v < db.size(); ++v) {
    size = std::max(size, glm::length(da[v]));
    worst = std::max(worst, glm::length(da[v] - db[v]));
  }
  return size > 0.0f ? worst / size : std::numeric_limits<float>::infinity();
}

}  // namespace transfer_fixture
