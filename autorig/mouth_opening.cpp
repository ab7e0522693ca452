#include "autorig/mouth_opening.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <queue>
#include <utility>

#include "autorig/face_frame.h"

namespace autorig {
namespace {

// The mouth's box where the lips are told apart, in eye spans: above and
// below the lip line, behind the lips' middle, and past the corners.
constexpr float kMouthBoxHeight = 0.2f;
constexpr float kMouthBoxDepth = 0.12f;
// Vertices this far above (below) the lip line are the upper (lower) lip.
constexpr float kLipSeed = 0.05f;
// Fewer seam vertices than this are no welded mouth.
constexpr size_t kMinSeamVertices = 3;

struct MouthBox {
  glm::vec3 lipCentre{0.0f};
  float left = 0.0f, right = 0.0f;  // the corners across the midline, eye spans
  float margin = 0.0f;              // past (or within) the corners, eye spans
};

// Linear albedo of the mouth bag: the dark red-brown of a mouth's inside in shadow.
constexpr glm::vec4 kMouthBagColour{0.10f, 0.025f, 0.02f, 1.0f};

// Appends a copy of vertex v (every attribute, its targets' deltas too) and returns its index.
uint32_t duplicateVertex(eng::Primitive& prim, uint32_t v) {
  const size_t n = prim.vertexCount();
  const size_t sets = prim.influenceSets();
  auto copy = [&](auto& values) {
    if (values.size() != n) return;
    const auto value = values[v];
    values.push_back(value);
  };
  copy(prim.positions);
  copy(prim.normals);
  copy(prim.texcoords);
  copy(prim.tangents);
  copy(prim.colors);
  for (size_t s = 0; s < sets; ++s) {
    const glm::u16vec4 joints = prim.joints[v * sets + s];
    const glm::vec4 weights = prim.jointWeights[v * sets + s];
    prim.joints.push_back(joints);
    prim.jointWeights.push_back(weights);
  }
  for (eng::MorphTarget& target : prim.targets) {
    copy(target.positions);
    copy(target.normals);
    copy(target.tangents);
  }
  return uint32_t(n);
}

std::string meshLabel(const eng::Model& model, size_t mesh) {
  const std::string& name = model.meshes[mesh].name;
  return name.empty() ? "mesh " + std::to_string(mesh) : name;
}

// The skin about the mouth, each vertex labelled by which lip it is nearer
// along the surface: distances grown from the vertices clearly above the lip
// line and from those clearly below, through the front of the mouth only (a
// mouth's inside joins the lips of any face). Lips that are separate meet
// only beyond the mouth corners; welded lips meet between them.
struct LipSides {
  std::vector<char> inMouth;      // the vertex is in the mouth's box
  std::vector<float> toUpper, toLower;  // distances along the edges
};

LipSides lipSides(const eng::Primitive& prim, const std::vector<glm::vec3>& world, const std::vector<FacePart>& parts,
                  const LandmarkFrame& frame, const MouthBox& box) {
  const size_t n = world.size();
  LipSides sides;
  sides.inMouth.assign(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (parts[v] != FacePart::Skin) continue;
    const float side = frame.sideOf(world[v]), above = frame.aboveLipLine(world[v]);
    const float depth = glm::dot(world[v] - box.lipCentre, frame.forward()) / frame.eyeSpan();
    sides.inMouth[v] = side > box.left - box.margin && side < box.right + box.margin && std::abs(above) < kMouthBoxHeight &&
                       depth > -kMouthBoxDepth;
  }
  std::vector<std::vector<uint32_t>> neighbours(n);
  for (size_t t = 0; t + 2 < prim.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = prim.indices[t + size_t(k)], b = prim.indices[t + size_t((k + 1) % 3)];
      if (a >= n || b >= n || !sides.inMouth[a] || !sides.inMouth[b]) continue;
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  auto grow = [&](float sign) {
    std::vector<float> distance(n, std::numeric_limits<float>::infinity());
    using Entry = std::pair<float, uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front;
    for (size_t v = 0; v < n; ++v)
      if (sides.inMouth[v] && sign * frame.aboveLipLine(world[v]) > kLipSeed) distance[v] = 0.0f, front.push({0.0f, uint32_t(v)});
    while (!front.empty()) {
      const auto [d, v] = front.top();
      front.pop();
      if (d > distance[v]) continue;
      for (uint32_t w : neighbours[v]) {
        const float through = d + glm::distance(world[v], world[w]);
        if (through < distance[w]) distance[w] = through, front.push({through, w});
      }
    }
    return distance;
  };
  sides.toUpper = grow(1.0f);
  sides.toLower = grow(-1.0f);
  return sides;
}

// Cuts the welded lips of one primitive; returns how many seam vertices got a copy.
size_t cutWeldedLips(eng::Primitive& prim, const PosedPrimitive& posed, const std::vector<FacePart>& parts,
                     const LandmarkFrame& frame, const MouthBox& box) {
  const std::vector<glm::vec3>& world = posed.positions;
  const size_t n = world.size();
  if (n != prim.vertexCount() || parts.size() != n) return 0;
  const LipSides sides = lipSides(prim, world, parts, frame, box);
  auto upper = [&](uint32_t v) { return sides.toUpper[v] < sides.toLower[v]; };
  auto labelled = [&](uint32_t v) { return v < n && sides.inMouth[v] && std::isfinite(std::min(sides.toUpper[v], sides.toLower[v])); };
  // The seam: upper-lip vertices between the corners that share a triangle
  // with a lower-lip vertex. Each gets a copy for the triangles that reach the
  // lower lip; past the corners the lips stay joined.
  std::vector<char> seam(n, 0);
  const size_t triangles = prim.indices.size() / 3;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* i = &prim.indices[t * 3];
    if (!labelled(i[0]) || !labelled(i[1]) || !labelled(i[2])) continue;
    const bool lower = !upper(i[0]) || !upper(i[1]) || !upper(i[2]);
    for (int k = 0; k < 3 && lower; ++k) {
      const float side = frame.sideOf(world[i[k]]);
      if (upper(i[k]) && side > box.left + box.margin && side < box.right - box.margin) seam[i[k]] = 1;
    }
  }
  if (size_t(std::count(seam.begin(), seam.end(), 1)) < kMinSeamVertices) return 0;
  std::vector<uint32_t> copyOf(n, std::numeric_limits<uint32_t>::max());
  size_t cut = 0;
  for (size_t t = 0; t < triangles; ++t) {
    uint32_t* i = &prim.indices[t * 3];
    if (!labelled(i[0]) || !labelled(i[1]) || !labelled(i[2])) continue;
    if (upper(i[0]) && upper(i[1]) && upper(i[2])) continue;
    for (int k = 0; k < 3; ++k) {
      if (!seam[i[k]]) continue;
      if (copyOf[i[k]] == std::numeric_limits<uint32_t>::max()) {
        copyOf[i[k]] = duplicateVertex(prim, i[k]);
        ++cut;
      }
      i[k] = copyOf[i[k]];
    }
  }
  return cut;
}

struct Ray {
  glm::vec3 origin, direction;
};

// Möller-Trumbore: whether the ray meets the triangle in front of its origin.
bool meets(const Ray& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  const glm::vec3 p = glm::cross(ray.direction, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return false;
  const float inv = 1.0f / det;
  const glm::vec3 s = ray.origin - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const glm::vec3 q = glm::cross(s, e1);
  const float w = glm::dot(ray.direction, q) * inv;
  if (w < 0.0f || u + w > 1.0f) return false;
  return glm::dot(e2, q) * inv > 0.0f;
}

struct Bowl {
  std::vector<glm::vec3> positions, normals;  // world space; normals point into the bowl
  std::vector<uint32_t> indices;
};

// The back half of an ellipsoid (radii along the face's side, up and
// forward), open towards the lips, its rim `rimDepth` behind `centre`.
Bowl makeBowl(const LandmarkFrame& frame, const glm::vec3& centre, const glm::vec3& radii) {
  constexpr int kRings = 8, kSegments = 24;
  Bowl bowl;
  const glm::vec3 axis[3] = {frame.side(), frame.up(), frame.forward()};
  auto at = [&](float phi, float theta) {
    const glm::vec3 unit(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), -std::cos(phi));
    return unit;
  };
  bowl.positions.push_back(centre - axis[2] * radii.z);  // the back pole
  bowl.normals.push_back(axis[2]);
  for (int r = 1; r <= kRings; ++r) {
    const float phi = 0.5f * std::numbers::pi_v<float> * float(r) / kRings;
    for (int s = 0; s < kSegments; ++s) {
      const glm::vec3 u = at(phi, 2.0f * std::numbers::pi_v<float> * float(s) / kSegments);
      bowl.positions.push_back(centre + axis[0] * (u.x * radii.x) + axis[1] * (u.y * radii.y) + axis[2] * (u.z * radii.z));
      const glm::vec3 outward = axis[0] * (u.x / radii.x) + axis[1] * (u.y / radii.y) + axis[2] * (u.z / radii.z);
      bowl.normals.push_back(-glm::normalize(outward));
    }
  }
  auto ringVertex = [&](int r, int s) { return uint32_t(1 + (r - 1) * kSegments + (s % kSegments)); };
  auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
    // Wound to face into the bowl (what an open mouth shows).
    const glm::vec3 normal = glm::cross(bowl.positions[b] - bowl.positions[a], bowl.positions[c] - bowl.positions[a]);
    if (glm::dot(normal, bowl.normals[a] + bowl.normals[b] + bowl.normals[c]) < 0.0f) std::swap(b, c);
    bowl.indices.insert(bowl.indices.end(), {a, b, c});
  };
  for (int s = 0; s < kSegments; ++s) triangle(0, ringVertex(1, s), ringVertex(1, s + 1));
  for (int r = 1; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      triangle(ringVertex(r, s), ringVertex(r + 1, s), ringVertex(r + 1, s + 1));
      triangle(ringVertex(r, s), ringVertex(r + 1, s + 1), ringVertex(r, s + 1));
    }
  return bowl;
}

struct SkinTriangles {
  std::vector<glm::vec3> corners;  // three per triangle, world space
};

bool behindTheSkin(const glm::vec3& p, const SkinTriangles& skin, const glm::vec3& forward) {
  const Ray ray{p, forward};
  for (size_t t = 0; t + 2 < skin.corners.size(); t += 3)
    if (meets(ray, skin.corners[t], skin.corners[t + 1], skin.corners[t + 2])) return true;
  return false;
}

// Moves each bowl vertex that the closed lips do not cover back (along the
// face's forward) until it lies behind the skin: the face curves back beside
// the mouth faster than the bowl does. False when one cannot be hidden.
bool tuckBehindTheSkin(Bowl& bowl, const SkinTriangles& skin, const LandmarkFrame& frame, const glm::vec3& lipCentre,
                       float mouthWidth) {
  constexpr int kSteps = 12;
  for (glm::vec3& p : bowl.positions) {
    const glm::vec3 d = p - lipCentre;
    const float x = glm::dot(d, frame.side()) / (0.5f * mouthWidth), y = glm::dot(d, frame.up()) / (0.15f * mouthWidth);
    if (x * x + y * y <= 1.0f) continue;  // seen only through the opening
    int step = 0;
    for (; step <= kSteps && !behindTheSkin(p, skin, frame.forward()); ++step) p -= frame.forward() * (0.05f * mouthWidth);
    if (step > kSteps) return false;
  }
  return true;
}

// Adds the mouth bag to the skin primitive nearest the lips; its vertex count, or 0 with a note why not.
size_t addMouthBag(eng::Model& face, const PosedFace& posed, const FaceParts& parts, const FaceLandmarks& landmarks,
                   const LandmarkFrame& frame, std::vector<std::string>& notes) {
  const auto& p = landmarks.points;
  glm::vec3 lipCentre(0.0f);
  for (size_t i = 60; i < 68; ++i) lipCentre += p[i] / 8.0f;
  const float mouthWidth = glm::length(p[54] - p[48]);
  // The skin primitive and vertex nearest the lips (the bag joins its mesh),
  // and the vertex nearest the nose's base (the bag moves as it does: above
  // the mouth, with the head, not the jaw).
  size_t host = posed.primitives.size();
  uint32_t anchor = 0;
  float nearest = std::numeric_limits<float>::max();
  SkinTriangles skin;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    const eng::Primitive& prim = face.meshes[pp.mesh].primitives[pp.primitive];
    for (size_t v = 0; v < pp.positions.size(); ++v)
      if (parts.vertexParts[i][v] == FacePart::Skin && glm::distance(pp.positions[v], lipCentre) < nearest)
        nearest = glm::distance(pp.positions[v], lipCentre), host = i;
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      const uint32_t* tri = &prim.indices[t];
      if (tri[0] >= pp.positions.size() || tri[1] >= pp.positions.size() || tri[2] >= pp.positions.size()) continue;
      if (parts.vertexParts[i][tri[0]] != FacePart::Skin) continue;
      if (glm::distance(pp.positions[tri[0]], lipCentre) > 2.0f * mouthWidth) continue;
      skin.corners.insert(skin.corners.end(), {pp.positions[tri[0]], pp.positions[tri[1]], pp.positions[tri[2]]});
    }
  }
  if (host == posed.primitives.size()) return 0;
  const PosedPrimitive& pp = posed.primitives[host];
  nearest = std::numeric_limits<float>::max();
  for (size_t v = 0; v < pp.positions.size(); ++v)
    if (parts.vertexParts[host][v] == FacePart::Skin && glm::distance(pp.positions[v], p[33]) < nearest)
      nearest = glm::distance(pp.positions[v], p[33]), anchor = uint32_t(v);

  // Behind the mouth corners (the deeper one), reaching above the lips and
  // below them as far as a dropped jaw opens them.
  const float cornerDepth = std::min(glm::dot(p[48] - lipCentre, frame.forward()), glm::dot(p[54] - lipCentre, frame.forward()));
  const glm::vec3 rimCentre = lipCentre + frame.forward() * (std::min(cornerDepth, 0.0f) - 0.1f * mouthWidth) -
                              frame.up() * (0.1f * mouthWidth);
  Bowl bowl;
  bool fits = false;
  for (float scale = 1.0f; scale > 0.5f && !fits; scale *= 0.85f) {
    bowl = makeBowl(frame, rimCentre, glm::vec3(0.62f, 0.6f, 0.6f) * (mouthWidth * scale));
    fits = tuckBehindTheSkin(bowl, skin, frame, lipCentre, mouthWidth);
  }
  const std::string label = meshLabel(face, pp.mesh);
  if (!fits) {
    notes.push_back(label + ": nothing inside the mouth, and no room for a mouth bag behind the lips "
                    "(an open mouth shows what is behind the face)");
    return 0;
  }

  eng::Mesh& mesh = face.meshes[pp.mesh];
  const eng::Primitive& hostPrim = mesh.primitives[pp.primitive];
  eng::Primitive bag;
  const glm::mat3 toLocal = pp.worldToLocal[anchor];
  for (size_t v = 0; v < bowl.positions.size(); ++v) {
    bag.positions.push_back(hostPrim.positions[anchor] + toLocal * (bowl.positions[v] - pp.positions[anchor]));
    bag.normals.push_back(glm::normalize(toLocal * bowl.normals[v]));
  }
  const size_t sets = hostPrim.influenceSets();
  for (size_t v = 0; v < bowl.positions.size(); ++v)
    for (size_t s = 0; s < sets; ++s) {
      bag.joints.push_back(hostPrim.joints[anchor * sets + s]);
      bag.jointWeights.push_back(hostPrim.jointWeights[anchor * sets + s]);
    }
  bag.indices = std::move(bowl.indices);
  bag.targets.resize(mesh.targetNames.size());  // empty: not moved by the face's own targets
  eng::Material material;
  material.name = "MouthInterior";
  material.baseColorFactor = kMouthBagColour;
  material.roughness = 0.9f;
  material.doubleSided = true;
  bag.material = int(face.materials.size());
  face.materials.push_back(std::move(material));
  const size_t count = bag.vertexCount();
  mesh.primitives.push_back(std::move(bag));
  notes.push_back(label + ": nothing inside the mouth (no teeth, no tongue): a mouth bag of " + std::to_string(count) +
                  " vertices added behind the lips");
  return count;
}

}  // namespace

MouthOpening openTheMouth(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks, const FaceParts& parts) {
  MouthOpening opening;
  if (parts.vertexParts.size() != posed.primitives.size()) return opening;
  const LandmarkFrame frame(landmarks);
  const auto& p = landmarks.points;
  MouthBox box;
  for (size_t i = 60; i < 68; ++i) box.lipCentre += p[i] / 8.0f;
  box.left = std::min(frame.sideOf(p[48]), frame.sideOf(p[54]));
  box.right = std::max(frame.sideOf(p[48]), frame.sideOf(p[54]));
  box.margin = 0.08f * (box.right - box.left);
  bool hasInside = false;
  for (const std::vector<FacePart>& vertexParts : parts.vertexParts)
    for (FacePart part : vertexParts)
      hasInside |= part == FacePart::UpperTeeth || part == FacePart::LowerTeeth || part == FacePart::Tongue;
  // The bag is placed from the face before the cut (the cut moves nothing).
  if (!hasInside) opening.bagVertices = addMouthBag(face, posed, parts, landmarks, frame, opening.notes);
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    const size_t cut = cutWeldedLips(face.meshes[pp.mesh].primitives[pp.primitive], pp, parts.vertexParts[i], frame, box);
    if (cut == 0) continue;
    opening.cutVertices += cut;
    opening.notes.push_back(meshLabel(face, pp.mesh) + ": lips welded along " + std::to_string(cut) +
                            " vertices, cut between the mouth corners");
  }
  return opening;
}

}  // namespace autorig
