#include "autorig/surface_cast.h"

#include "engine/scene/ray_triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "autorig/face_parts.h"

namespace autorig {

namespace {

const std::vector<uint32_t>* triangleIndices(const eng::Model& model, const PosedPrimitive& p) {
  if (p.mesh >= model.meshes.size() || p.primitive >= model.meshes[p.mesh].primitives.size()) return nullptr;
  return &model.meshes[p.mesh].primitives[p.primitive].indices;
}

bool validTriangle(const std::vector<uint32_t>& indices, size_t t, size_t vertexCount) {
  return indices[3 * t] < vertexCount && indices[3 * t + 1] < vertexCount && indices[3 * t + 2] < vertexCount;
}

// Ericson, Real-Time Collision Detection 5.1.5.
glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const float denom = 1.0f / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Whether the triangles' normals (counter-clockwise) point away from the
// primitive's centre, as glTF's front faces do; a mirrored node or an
// exporter's flipped winding turns them in, and the casts' notion of which
// side faces the camera with them.
bool windsOutward(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
  glm::dvec3 centre(0.0);
  for (const glm::vec3& v : positions) centre += glm::dvec3(v);
  centre /= double(std::max<size_t>(positions.size(), 1));
  double outward = 0.0;
  for (size_t t = 0; t < indices.size() / 3; ++t) {
    if (!validTriangle(indices, t, positions.size())) continue;
    const glm::dvec3 a(positions[indices[3 * t]]), b(positions[indices[3 * t + 1]]), c(positions[indices[3 * t + 2]]);
    outward += glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre);
  }
  return outward >= 0.0;
}

}  // namespace

SurfaceCaster::SurfaceCaster(const eng::Model& model, const PosedFace& posed, const std::vector<bool>& cast,
                             const PictureCamera& camera)
    : posed_(&posed), camera_(camera), inverse_(glm::inverse(camera.viewProjection)) {
  bins_.resize(size_t(cells_) * size_t(cells_));
  const glm::vec4 nearH = inverse_ * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), farH = inverse_ * glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  nearCentre_ = glm::vec3(nearH) / nearH.w;
  forward_ = glm::normalize(glm::vec3(farH) / farH.w - nearCentre_);
  indices_.assign(posed.primitives.size(), nullptr);
  outward_.assign(posed.primitives.size(), true);
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    if (pi >= cast.size() || !cast[pi]) continue;
    const PosedPrimitive& p = posed.primitives[pi];
    const std::vector<uint32_t>* indices = triangleIndices(model, p);
    if (!indices) continue;
    indices_[pi] = indices;
    outward_[pi] = windsOutward(p.positions, *indices);
    std::vector<std::optional<glm::vec2>> projected(p.positions.size());
    for (size_t v = 0; v < p.positions.size(); ++v) projected[v] = project(p.positions[v]);
    for (size_t t = 0; t < indices->size() / 3; ++t) {
      if (!validTriangle(*indices, t, p.positions.size())) continue;
      glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      bool inFront = true;
      for (int k = 0; k < 3; ++k) {
        const auto& s = projected[(*indices)[3 * t + size_t(k)]];
        if (!s) inFront = false;
        else lo = glm::min(lo, *s), hi = glm::max(hi, *s);
      }
      if (!inFront || hi.x < 0.0f || hi.y < 0.0f || lo.x >= camera.imageSize.x || lo.y >= camera.imageSize.y) continue;
      // Clamped as floats first: a vertex far off the picture is no int.
      const glm::vec2 last(float(cells_ - 1));
      const glm::vec2 cells = float(cells_) / camera.imageSize;
      const glm::ivec2 c0(glm::clamp(glm::floor(lo * cells), glm::vec2(0.0f), last));
      const glm::ivec2 c1(glm::clamp(glm::floor(hi * cells), glm::vec2(0.0f), last));
      for (int y = c0.y; y <= c1.y; ++y)
        for (int x = c0.x; x <= c1.x; ++x) bins_[size_t(y * cells_ + x)].push_back({uint32_t(pi), uint32_t(t)});
    }
  }
}

std::optional<glm::vec2> projectToPicture(const PictureCamera& camera, const glm::vec3& world) {
  const glm::vec4 clip = camera.viewProjection * glm::vec4(world, 1.0f);
  if (!(clip.w > 1e-6f)) return std::nullopt;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  if (!std::isfinite(ndc.x) || !std::isfinite(ndc.y)) return std::nullopt;
  return (ndc * 0.5f + 0.5f) * camera.imageSize;
}

int SurfaceCaster::cellOf(glm::vec2 pixel) const {
  const glm::vec2 c = glm::floor(pixel / camera_.imageSize * float(cells_));
  if (!(c.x >= 0.0f && c.y >= 0.0f && c.x < float(cells_) && c.y < float(cells_))) return -1;
  return int(c.y) * cells_ + int(c.x);
}

std::optional<SurfacePoint> SurfaceCaster::cast(glm::vec2 pixel, float reachPixels, float maxDepth) const {
  const glm::vec2 ndc = pixel / camera_.imageSize * 2.0f - 1.0f;
  const glm::vec4 nearH = inverse_ * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 farH = inverse_ * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 origin = glm::vec3(nearH) / nearH.w;
  const glm::vec3 dir = glm::normalize(glm::vec3(farH) / farH.w - origin);
  const int cell = cellOf(pixel);
  if (cell < 0) return std::nullopt;
  float bestT = std::numeric_limits<float>::max();
  std::optional<SurfacePoint> best;
  bool bestFaces = false;
  for (const TriangleRef& ref : bins_[size_t(cell)]) {
    const PosedPrimitive& p = posed_->primitives[ref.primitive];
    const std::vector<uint32_t>& idx = *indices_[ref.primitive];
    const glm::vec3& a = p.positions[idx[3 * ref.triangle]];
    const glm::vec3& b = p.positions[idx[3 * ref.triangle + 1]];
    const glm::vec3& c = p.positions[idx[3 * ref.triangle + 2]];
    const std::optional<eng::RayTriangleHit> hit = eng::intersectRayTriangle(origin, dir, a, b, c);
    const std::optional<float> t = hit ? std::optional<float>(hit->distance) : std::nullopt;
    if (!t || *t >= bestT) continue;
    bestT = *t;
    best = SurfacePoint{ref.primitive, origin + dir * *t, true};
    bestFaces = (glm::dot(glm::cross(b - a, c - a), dir) < 0.0f) == outward_[ref.primitive];
  }
  if (best && bestFaces && depth(best->position) <= maxDepth) return best;
  // The inside of the head first: the ray went through an opening (an eye,
  // parted lips), and the opening's rim is meant: the nearest vertex of a
  // triangle that faces the camera. No hit: the point lies just off the
  // outline, and the outline is meant.
  return nearestVertex(pixel, reachPixels, best ? &dir : nullptr, maxDepth);
}

// The vertex that lands nearest the pixel, within reach; with `facing`, only
// those of triangles that face a ray along it (the lid's rim beside an eye
// opening, not the inside of the skull behind it).
std::optional<SurfacePoint> SurfaceCaster::nearestVertex(glm::vec2 pixel, float reachPixels, const glm::vec3* facing,
                                                         float maxDepth) const {
  const glm::vec2 cells = float(cells_) / camera_.imageSize;
  const glm::vec2 last(float(cells_ - 1));
  const glm::ivec2 c0(glm::clamp(glm::floor((pixel - reachPixels) * cells), glm::vec2(0.0f), last));
  const glm::ivec2 c1(glm::clamp(glm::floor((pixel + reachPixels) * cells), glm::vec2(0.0f), last));
  float bestScore = std::numeric_limits<float>::max();
  std::optional<SurfacePoint> best;
  for (int y = c0.y; y <= c1.y; ++y)
    for (int x = c0.x; x <= c1.x; ++x)
      for (const TriangleRef& ref : bins_[size_t(y * cells_ + x)]) {
        const PosedPrimitive& p = posed_->primitives[ref.primitive];
        const std::vector<uint32_t>& idx = *indices_[ref.primitive];
        const uint32_t* corner = &idx[3 * ref.triangle];
        const glm::vec3 n = glm::cross(p.positions[corner[1]] - p.positions[corner[0]],
                                       p.positions[corner[2]] - p.positions[corner[0]]);
        if (facing && (glm::dot(n, *facing) < 0.0f) != outward_[ref.primitive]) continue;
        for (int k = 0; k < 3; ++k) {
          const glm::vec3& v = p.positions[corner[k]];
          const std::optional<glm::vec2> s = project(v);
          if (!s || depth(v) > maxDepth) continue;
          const float away = glm::distance(*s, pixel);
          if (away > reachPixels || away >= bestScore) continue;
          bestScore = away;
          best = SurfacePoint{ref.primitive, v, false};
        }
      }
  return best;
}

namespace {

// Named as skin or not named at all, and not see-through: a lens is no skin
// the detector saw (Ready Player Me's glasses, in the transparent primitive a
// texture atlas export makes, took the eyes' points 1.5 cm in front of the lids).
bool mayBeSkin(const eng::Model& model, const PosedPrimitive& p) {
  const std::optional<FacePart> named = facePartFromNames(model, p);
  const int material = model.meshes[p.mesh].primitives[p.primitive].material;
  const bool seeThrough = material >= 0 && size_t(material) < model.materials.size() &&
                          model.materials[size_t(material)].alphaMode == eng::AlphaMode::Blend;
  return (!named || *named == FacePart::Skin) && !seeThrough;
}

}  // namespace

std::vector<bool> outerSkinPrimitives(const eng::Model& model, const PosedFace& posed) {
  const size_t n = posed.primitives.size();
  std::vector<glm::vec3> lo(n, glm::vec3(std::numeric_limits<float>::max()));
  std::vector<glm::vec3> hi(n, glm::vec3(-std::numeric_limits<float>::max()));
  for (size_t i = 0; i < n; ++i)
    for (const glm::vec3& v : posed.primitives[i].positions) lo[i] = glm::min(lo[i], v), hi[i] = glm::max(hi[i], v);
  auto enclosed = [&](size_t i) {
    for (size_t o = 0; o < n; ++o)
      if (o != i && glm::all(glm::lessThan(lo[o], lo[i])) && glm::all(glm::lessThan(hi[i], hi[o]))) return true;
    return false;
  };
  std::vector<bool> outer(n, false);
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    outer[i] = mayBeSkin(model, posed.primitives[i]) && !enclosed(i);
    any = any || outer[i];
  }
  if (!any) outer.assign(n, true);
  return outer;
}

std::vector<bool> seenSkinPrimitives(const eng::Model& model, const PosedFace& posed, const PictureCamera& camera) {
  std::vector<bool> outer = outerSkinPrimitives(model, posed);
  const size_t n = posed.primitives.size();
  std::vector<bool> skin(n, false);
  for (size_t i = 0; i < n; ++i) skin[i] = mayBeSkin(model, posed.primitives[i]);
  std::vector<size_t> enclosed;
  for (size_t i = 0; i < n; ++i)
    if (skin[i] && !outer[i]) enclosed.push_back(i);
  if (enclosed.empty()) return outer;
  // Until 2026-12-07 an enclosed piece was always passed through: facecap
  // with its lips a primitive of their own had its mouth's and nose's
  // landmarks cast onto the mouth's inside, 0.4-0.8 eye spans deep.
  constexpr size_t kSamples = 400;
  const SurfaceCaster caster(model, posed, skin, camera);
  for (size_t i : enclosed) {
    const std::vector<glm::vec3>& positions = posed.primitives[i].positions;
    const size_t step = std::max<size_t>(1, positions.size() / kSamples);
    size_t tried = 0, seen = 0;
    for (size_t v = 0; v < positions.size(); v += step) {
      const std::optional<glm::vec2> pixel = caster.project(positions[v]);
      if (!pixel) continue;
      ++tried;
      const std::optional<SurfacePoint> hit = caster.cast(*pixel, 1.0f);
      seen += hit && hit->hit && hit->primitive == i;
    }
    if (tried > 0 && 2 * seen > tried) outer[i] = true;
  }
  return outer;
}

float distanceToSurface(const eng::Model& model, const PosedFace& posed, const glm::vec3& point,
                        const std::vector<bool>& among) {
  float best = std::numeric_limits<float>::infinity();
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    if (!among.empty() && (pi >= among.size() || !among[pi])) continue;
    const PosedPrimitive& p = posed.primitives[pi];
    const std::vector<uint32_t>* indices = triangleIndices(model, p);
    if (!indices || p.positions.empty()) continue;
    // A primitive whose box lies farther than the best so far is skipped.
    glm::vec3 lo = p.positions[0], hi = p.positions[0];
    for (const glm::vec3& v : p.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
    if (glm::distance(glm::clamp(point, lo, hi), point) >= best) continue;
    for (size_t t = 0; t < indices->size() / 3; ++t) {
      if (!validTriangle(*indices, t, p.positions.size())) continue;
      const glm::vec3 q = closestOnTriangle(point, p.positions[(*indices)[3 * t]], p.positions[(*indices)[3 * t + 1]],
                                            p.positions[(*indices)[3 * t + 2]]);
      best = std::min(best, glm::distance(q, point));
    }
  }
  return best;
}

}  // namespace autorig
