#include "autorig/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace autorig {
namespace {

// Triangles per cell on average: a few keeps both the grid and each shell small.
constexpr float kTrianglesPerCell = 2.0f;
constexpr int kMaxCellsPerAxis = 256;
// cos(70 degrees): how far a matched triangle may turn from the query's normal.
constexpr float kMinFacing = 0.34f;

}  // namespace

glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            glm::vec3& barycentric) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return barycentric = {1, 0, 0}, a;
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return barycentric = {0, 1, 0}, b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float v = d1 / (d1 - d3);
    return barycentric = {1 - v, v, 0}, a + v * ab;
  }
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return barycentric = {0, 0, 1}, c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float w = d2 / (d2 - d6);
    return barycentric = {1 - w, 0, w}, a + w * ac;
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return barycentric = {0, 1 - w, w}, b + w * (c - b);
  }
  const float sum = va + vb + vc;
  if (!(std::abs(sum) > 0.0f)) return barycentric = {1, 0, 0}, a;  // a degenerate triangle
  const float v = vb / sum, w = vc / sum;
  return barycentric = {1 - v - w, v, w}, a + ab * v + ac * w;
}

namespace {

// +1 when the triangles wind so their normals point away from the surface's
// middle (outwards, as glTF's counter-clockwise front faces do on a head), -1
// when the file winds them the other way: normals are compared outward-facing.
float outwardSign(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> triangles) {
  glm::dvec3 middle(0.0);
  for (const auto& t : triangles) middle += glm::dvec3(positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0;
  if (!triangles.empty()) middle /= double(triangles.size());
  double outward = 0.0;
  for (const auto& t : triangles) {
    const glm::vec3 n = glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
    outward += double(glm::dot(n, (positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0f - glm::vec3(middle)));
  }
  return outward < 0.0 ? -1.0f : 1.0f;
}

}  // namespace

std::vector<glm::vec3> vertexNormals(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> triangles) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (const auto& t : triangles) {
    const glm::vec3 n = glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
    for (uint32_t v : t) normals[v] += n;
  }
  const float sign = outwardSign(positions, triangles);
  for (glm::vec3& n : normals) {
    const float length = glm::length(n);
    n = length > 0.0f ? sign * n / length : glm::vec3(0.0f);
  }
  return normals;
}

TriangleGrid::TriangleGrid(std::span<const glm::vec3> positions, std::span<const std::array<uint32_t, 3>> triangles,
                           std::span<const FaceRegion> regions)
    : positions_(positions.begin(), positions.end()), triangles_(triangles.begin(), triangles.end()) {
  regionBits_.assign(triangles.size(), 0u);
  if (regions.size() == positions.size())
    for (size_t i = 0; i < triangles_.size(); ++i)
      for (uint32_t v : triangles_[i]) regionBits_[i] |= 1u << unsigned(regions[v]);
  normals_.resize(triangles_.size());
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const auto& t = triangles_[i];
    const glm::vec3 n = glm::cross(positions_[t[1]] - positions_[t[0]], positions_[t[2]] - positions_[t[0]]);
    const float length = glm::length(n);
    normals_[i] = length > 0.0f ? n / length : glm::vec3(0.0f);
  }
  const float sign = outwardSign(positions_, triangles_);
  for (glm::vec3& n : normals_) n *= sign;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const auto& t : triangles_)
    for (uint32_t v : t) lo = glm::min(lo, positions_[v]), hi = glm::max(hi, positions_[v]);
  if (triangles_.empty()) lo = hi = glm::vec3(0.0f);
  const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
  const float volume = size.x * size.y * size.z;
  const float cells = std::max(1.0f, float(triangles_.size()) / kTrianglesPerCell);
  cell_ = std::max(std::cbrt(volume / cells), std::max({size.x, size.y, size.z}) / float(kMaxCellsPerAxis));
  min_ = lo;
  dims_ = glm::clamp(glm::ivec3(glm::floor(size / cell_)) + 1, glm::ivec3(1), glm::ivec3(kMaxCellsPerAxis + 1));
  const size_t cellCount = size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z);
  // Two passes (count, then fill) over each triangle's bounding cells.
  std::vector<uint32_t> counts(cellCount + 1, 0);
  auto forCells = [&](const std::array<uint32_t, 3>& t, auto&& visit) {
    glm::vec3 tlo = glm::min(glm::min(positions_[t[0]], positions_[t[1]]), positions_[t[2]]);
    glm::vec3 thi = glm::max(glm::max(positions_[t[0]], positions_[t[1]]), positions_[t[2]]);
    glm::ivec3 a = cellOf(tlo), b = cellOf(thi);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) visit(cellIndex({x, y, z}));
  };
  for (const auto& t : triangles_) forCells(t, [&](size_t cell) { ++counts[cell + 1]; });
  for (size_t i = 1; i <= cellCount; ++i) counts[i] += counts[i - 1];
  cellStart_ = counts;
  cellTriangles_.resize(counts[cellCount]);
  for (uint32_t i = 0; i < triangles_.size(); ++i) forCells(triangles_[i], [&](size_t cell) { cellTriangles_[counts[cell]++] = i; });
}

glm::ivec3 TriangleGrid::cellOf(const glm::vec3& p) const {
  return glm::clamp(glm::ivec3(glm::floor((p - min_) / cell_)), glm::ivec3(0), dims_ - 1);
}

namespace {

// Whether a triangle with corners in `bits` is refused to a query that
// refuses `refused` (the query's own region is its opposite). The lips part
// up to their corners, so a triangle that reaches the other lip there is
// refused: it would give the upper lip the lower lip's motion and tear it.
// The lids meet at still corners: a triangle spanning them is both lids'.
bool refuses(uint32_t bits, FaceRegion refused) {
  if (refused == FaceRegion::None || !(bits >> unsigned(refused) & 1u)) return false;
  const bool lip = refused == FaceRegion::UpperLip || refused == FaceRegion::LowerLip;
  return lip || !(bits >> unsigned(opposite(refused)) & 1u);
}

}  // namespace

ClosestPoint TriangleGrid::closest(const glm::vec3& p, FaceRegion refused, float maxDistance, const glm::vec3& facing) const {
  const bool checkFacing = facing != glm::vec3(0.0f);
  ClosestPoint best;
  best.distance = maxDistance;
  if (triangles_.empty() || !std::isfinite(p.x + p.y + p.z)) return best;
  // Distance from p to the grid's box: shells nearer than that hold nothing.
  const glm::vec3 outside = glm::max(glm::max(min_ - p, p - (min_ + glm::vec3(dims_) * cell_)), glm::vec3(0.0f));
  if (glm::length(outside) > maxDistance) return best;
  const glm::ivec3 centre = cellOf(p);
  const int maxShell = std::max({dims_.x, dims_.y, dims_.z});
  for (int shell = 0; shell <= maxShell; ++shell) {
    // Every cell of this shell is at least (shell - 1) cells away from p.
    if (best.found && float(shell - 1) * cell_ > best.distance) break;
    if (float(shell - 1) * cell_ > maxDistance + glm::length(outside)) break;
    const glm::ivec3 lo = glm::max(centre - shell, glm::ivec3(0)), hi = glm::min(centre + shell, dims_ - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          if (std::max({std::abs(x - centre.x), std::abs(y - centre.y), std::abs(z - centre.z)}) != shell) continue;
          const size_t cell = cellIndex({x, y, z});
          for (uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
            const uint32_t i = cellTriangles_[k];
            if (refuses(regionBits_[i], refused)) continue;
            if (checkFacing && glm::dot(normals_[i], facing) < kMinFacing) continue;
            const auto& t = triangles_[i];
            glm::vec3 bary;
            const glm::vec3 q = closestOnTriangle(p, positions_[t[0]], positions_[t[1]], positions_[t[2]], bary);
            const float d = glm::length(q - p);
            if (d < best.distance || (!best.found && d <= maxDistance)) {
              best = ClosestPoint{.triangle = i, .barycentric = bary, .position = q, .distance = d, .found = true};
            }
          }
        }
  }
  return best;
}

}  // namespace autorig
