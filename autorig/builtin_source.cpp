#include "autorig/builtin_source.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace autorig {
namespace {

// iBUG-68 in the head's front plane (x: the subject's left, y: up), metres,
// placed from data/head_landmarks.json's features: eyeballs at
// (+-0.0335, 0.009), mouth corners at +-0.024, the lips' seam at -0.0497, the
// chin at -0.083.
constexpr std::array<std::array<float, 2>, kLandmarkCount> kHeadLayout{{
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

// bake/head's primitive order in mesh "Head" (bake/head/head_generator.h).
constexpr size_t kUpperTeethPrimitive = 2;

FacePart partOf(const eng::Model& head, const PosedPrimitive& p) {
  const eng::Mesh& mesh = head.meshes[p.mesh];
  if (mesh.name == "EyeRight") return FacePart::EyeballRight;
  if (mesh.name == "EyeLeft") return FacePart::EyeballLeft;
  const int material = mesh.primitives[p.primitive].material;
  const std::string name = material >= 0 ? head.materials[size_t(material)].name : "";
  // The mouth's inside moves with the lips in the head's units: it is skin here.
  if (name == "Skin" || name == "Ear" || name == "MouthInterior") return FacePart::Skin;
  if (name == "Tongue") return FacePart::Tongue;
  if (name == "Teeth") return p.primitive == kUpperTeethPrimitive ? FacePart::UpperTeeth : FacePart::LowerTeeth;
  return FacePart::Other;
}

// The frontmost skin hit of the ray from (x, y, +inf) along -Z (barycentrics
// in the xy plane: the ray is axis-aligned).
std::optional<glm::vec3> castAlongMinusZ(const eng::Model& head, const PosedFace& posed, const FaceParts& parts,
                                         float x, float y) {
  std::optional<glm::vec3> best;
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    const PosedPrimitive& p = posed.primitives[pi];
    const eng::Primitive& primitive = head.meshes[p.mesh].primitives[p.primitive];
    for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
      const uint32_t ia = primitive.indices[i], ib = primitive.indices[i + 1], ic = primitive.indices[i + 2];
      if (std::max({ia, ib, ic}) >= p.positions.size() || parts.vertexParts[pi][ia] != FacePart::Skin) continue;
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

FaceParts headParts(const eng::Model& head, const PosedFace& posed) {
  FaceParts parts;
  std::array<glm::vec3, 2> sum{};
  std::array<size_t, 2> count{};
  for (const PosedPrimitive& p : posed.primitives) {
    const FacePart part = partOf(head, p);
    parts.vertexParts.emplace_back(p.positions.size(), part);
    const int eye = part == FacePart::EyeballRight ? 0 : part == FacePart::EyeballLeft ? 1 : -1;
    if (eye < 0) continue;
    for (const glm::vec3& v : p.positions) sum[size_t(eye)] += v, ++count[size_t(eye)];
  }
  for (size_t e = 0; e < 2; ++e)
    if (count[e] > 0) parts.eyeCentres[e] = sum[e] / float(count[e]);
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    const FacePart part = parts.vertexParts[pi].empty() ? FacePart::Other : parts.vertexParts[pi][0];
    const int eye = part == FacePart::EyeballRight ? 0 : part == FacePart::EyeballLeft ? 1 : -1;
    if (eye < 0) continue;
    for (const glm::vec3& v : posed.primitives[pi].positions)
      parts.eyeRadii[size_t(eye)] = std::max(parts.eyeRadii[size_t(eye)], glm::length(v - parts.eyeCentres[size_t(eye)]));
  }
  parts.eyeballsFound = count[0] > 0 && count[1] > 0;
  return parts;
}

}  // namespace

eng::Result<SourceFace> builtInSource(const eng::Model& head) {
  SourceFace source{.model = &head, .posed = poseAtRest(head), .landmarks = {}, .parts = {}};
  source.parts = headParts(head, source.posed);
  if (!source.parts.eyeballsFound)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "built-in head: no EyeLeft and EyeRight meshes (is this data/head.glb?)");
  source.landmarks.source = "the built-in head's layout (autorig/builtin_source.cpp)";
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const std::optional<glm::vec3> hit = castAlongMinusZ(head, source.posed, source.parts, kHeadLayout[i][0], kHeadLayout[i][1]);
    if (!hit)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "built-in head: landmark " + std::to_string(i) +
                                                                 " of 68 misses its skin (is this data/head.glb?)");
    source.landmarks.points[i] = *hit;
  }
  return source;
}

}  // namespace autorig
