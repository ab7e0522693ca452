#include "autorig/builtin_source.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace autorig {
namespace {

// iBUG-68 in the head's front plane (x: the subject's left, y: up), metres:
// where dlib's shape predictor puts them on a front view of the head
// (app::findFaceLandmarks, face box 259 px, confidence 2.36), made symmetric,
// so the source's points mean what a detected face's points mean (the jaw
// line's top at the ears, the inner lips on the lips' inner edges).
constexpr std::array<std::array<float, 2>, kLandmarkCount> kHeadLayout{{
    {-0.0782f, 0.0237f}, {-0.0731f, 0.0023f}, {-0.0630f, -0.0168f}, {-0.0589f, -0.0345f}, {-0.0514f, -0.0515f},
    {-0.0396f, -0.0661f}, {-0.0266f, -0.0787f}, {-0.0142f, -0.0896f}, {0.0000f, -0.0921f}, {0.0142f, -0.0896f},
    {0.0266f, -0.0787f}, {0.0396f, -0.0661f}, {0.0514f, -0.0515f}, {0.0589f, -0.0345f}, {0.0630f, -0.0168f},
    {0.0731f, 0.0023f}, {0.0782f, 0.0237f},
    {-0.0601f, 0.0253f}, {-0.0497f, 0.0322f}, {-0.0370f, 0.0344f}, {-0.0238f, 0.0330f}, {-0.0118f, 0.0281f},
    {0.0118f, 0.0281f}, {0.0238f, 0.0330f}, {0.0370f, 0.0344f}, {0.0497f, 0.0322f}, {0.0601f, 0.0253f},
    {0.0000f, 0.0118f}, {0.0000f, 0.0009f}, {0.0000f, -0.0094f}, {0.0000f, -0.0200f},
    {-0.0090f, -0.0293f}, {-0.0046f, -0.0308f}, {0.0000f, -0.0323f}, {0.0046f, -0.0308f}, {0.0090f, -0.0293f},
    {-0.0449f, 0.0109f}, {-0.0365f, 0.0142f}, {-0.0266f, 0.0141f}, {-0.0185f, 0.0080f}, {-0.0274f, 0.0046f},
    {-0.0375f, 0.0046f}, {0.0185f, 0.0080f}, {0.0266f, 0.0141f}, {0.0365f, 0.0142f}, {0.0449f, 0.0109f},
    {0.0375f, 0.0046f}, {0.0274f, 0.0046f},
    {-0.0214f, -0.0511f}, {-0.0132f, -0.0468f}, {-0.0054f, -0.0445f}, {0.0000f, -0.0460f}, {0.0054f, -0.0445f},
    {0.0132f, -0.0468f}, {0.0214f, -0.0511f}, {0.0138f, -0.0592f}, {0.0059f, -0.0624f}, {0.0000f, -0.0628f},
    {-0.0059f, -0.0624f}, {-0.0138f, -0.0592f},
    {-0.0179f, -0.0515f}, {-0.0054f, -0.0495f}, {0.0000f, -0.0499f}, {0.0054f, -0.0495f}, {0.0179f, -0.0515f},
    {0.0054f, -0.0558f}, {0.0000f, -0.0563f}, {-0.0054f, -0.0558f},
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
