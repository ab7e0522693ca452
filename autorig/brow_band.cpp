#include "autorig/brow_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "autorig/face_frame.h"
#include "autorig/texture_sampler.h"

namespace autorig {
namespace {

// Where a brow is looked for, in eye spans: from this far over the upper
// lid to this far over the brow line, and this far past the brow's ends.
constexpr float kOverLid = 0.03f;
constexpr float kOverLine = 0.06f;
constexpr float kPastEnds = 0.03f;
// A triangle's colour is looked at from this share of the way from the
// upper lid to the brow line up (the brows of the faces judged: Ready
// Player Me's 0.42-1, the built-in head's 0.63-1).
constexpr float kOverLidShare = 0.5f;
// The forehead the brow is told from: this band over the brow line.
constexpr float kForeheadFrom = 0.12f, kForeheadTo = 0.4f;
// Covered where the skin's lightness (luminance, sRGB-encoded as seen) is
// this low against the forehead's median: fully at kDark, not at all from
// kLight. Ready Player Me's brows are 0.19-0.35 of the forehead, the shadow
// painted in its lids' crease 0.53 (taken for brow at 0.8, the brows came
// out 0.2 eye spans thick and their matches moved down, not up); the
// built-in head's brows, half over the skin, are 0.74: it is the source.
constexpr float kDark = 0.4f, kLight = 0.5f;
// A brow reaching further under its line (eye spans) is something else: hair, a shadow.
constexpr float kMaxReach = 0.3f;
constexpr size_t kMinCovered = 3;

// A polyline in the face plane (side, up), sorted by side: its height at x, held flat past its ends.
float heightAt(std::span<const glm::vec2> line, float x) {
  if (x <= line.front().x) return line.front().y;
  for (size_t i = 1; i < line.size(); ++i)
    if (x <= line[i].x) {
      const float t = (x - line[i - 1].x) / std::max(line[i].x - line[i - 1].x, 1e-9f);
      return glm::mix(line[i - 1].y, line[i].y, t);
    }
  return line.back().y;
}

// Lightness as seen: linear luminance, sRGB-encoded (a gamma of 2.2).
float lightness(const glm::vec3& linear) {
  return std::pow(std::max(glm::dot(linear, glm::vec3(0.2126f, 0.7152f, 0.0722f)), 0.0f), 1.0f / 2.2f);
}

// The skin's colour as seen (the material's factor times its texture) at a
// vertex or over a triangle; nullopt where the material has no texture (one
// colour everywhere: nothing to tell a brow by).
class SkinColour {
 public:
  SkinColour(const eng::Model& face, const PosedFace& posed, const FaceSurface& surface)
      : surface_(surface), images_(surface.positions.size(), nullptr), uvs_(surface.positions.size()),
        factors_(surface.positions.size()) {
    for (size_t v = 0; v < surface.positions.size(); ++v) {
      const PosedPrimitive& pp = posed.primitives[surface.vertices[v].primitive];
      const eng::Primitive& primitive = face.meshes[pp.mesh].primitives[pp.primitive];
      if (primitive.material < 0 || size_t(primitive.material) >= face.materials.size()) continue;
      const eng::Material& m = face.materials[size_t(primitive.material)];
      if (m.baseColorImage < 0 || size_t(m.baseColorImage) >= face.images.size()) continue;
      const eng::Image& image = face.images[size_t(m.baseColorImage)];
      const uint32_t vertex = surface.vertices[v].vertex;
      if (!decoded(image) || vertex >= primitive.texcoords.size()) continue;
      images_[v] = &image;
      uvs_[v] = primitive.texcoords[vertex];
      factors_[v] = glm::vec3(m.baseColorFactor);
    }
  }
  std::optional<float> at(size_t v) const {
    if (!images_[v]) return std::nullopt;
    return lightness(factors_[v] * glm::vec3(Sampler(*images_[v])(uvs_[v])));
  }
  // The darkest of a few points over the triangle (its corners, its edges'
  // middles and its centre: a brow painted across a coarse mesh's triangle
  // may miss every corner) where `looked(position)`; nullopt where none is.
  template <typename Where>
  std::optional<float> darkestOn(const std::array<uint32_t, 3>& t, Where looked) const {
    const eng::Image* image = images_[t[0]];
    if (!image || images_[t[1]] != image || images_[t[2]] != image) return std::nullopt;
    const Sampler sample(*image);
    constexpr std::array<glm::vec3, 7> kPoints{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5f, 0.5f, 0}, {0, 0.5f, 0.5f},
                                                {0.5f, 0, 0.5f}, {1 / 3.0f, 1 / 3.0f, 1 / 3.0f}}};
    std::optional<float> darkest;
    for (const glm::vec3& w : kPoints) {
      if (!looked(w.x * surface_.positions[t[0]] + w.y * surface_.positions[t[1]] + w.z * surface_.positions[t[2]])) continue;
      const glm::vec2 uv = w.x * uvs_[t[0]] + w.y * uvs_[t[1]] + w.z * uvs_[t[2]];
      darkest = std::min(darkest.value_or(1e30f), lightness(factors_[t[0]] * glm::vec3(sample(uv))));
    }
    return darkest;
  }

 private:
  const FaceSurface& surface_;
  std::vector<const eng::Image*> images_;
  std::vector<glm::vec2> uvs_;
  std::vector<glm::vec3> factors_;
};

float median(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
  return values[values.size() / 2];
}

// How much brow each vertex about a brow is: a brow part all of it; skin as
// much as the darkest of its triangles is painted brow against the
// forehead's lightness `reference` (none without one).
template <typename Plane>
std::vector<float> paintedCoverage(const BrowBand::Brow& brow, const FaceSurface& surface, const SkinColour& colour,
                                   float reference, const Plane& plane, std::span<const glm::vec2> line,
                                   std::span<const glm::vec2> lid) {
  std::vector<int> aboutIndex(surface.positions.size(), -1);
  for (size_t i = 0; i < brow.about.size(); ++i) aboutIndex[brow.about[i]] = int(i);
  std::vector<float> coverage(brow.about.size(), 0.0f);
  for (size_t i = 0; i < brow.about.size(); ++i)
    if (surface.parts[brow.about[i]] == FacePart::Brows) coverage[i] = 1.0f;
  if (!(reference > 0.0f)) return coverage;
  for (const std::array<uint32_t, 3>& t : surface.triangles) {
    if (aboutIndex[t[0]] < 0 && aboutIndex[t[1]] < 0 && aboutIndex[t[2]] < 0) continue;
    // Looked at only over the middle between lid and brow line: below,
    // a low brow's triangles reach the shadow painted in the lid's crease
    // and the lashes, and Ready Player Me's lids rose with the brows.
    const std::optional<float> darkest = colour.darkestOn(t, [&](const glm::vec3& p) {
      const glm::vec2 q = plane(p);
      const float lidAt = heightAt(lid, q.x);
      return q.y > lidAt + kOverLidShare * (heightAt(line, q.x) - lidAt);
    });
    if (!darkest) continue;
    const float c = 1.0f - glm::smoothstep(kDark, kLight, *darkest / reference);
    for (uint32_t v : t)
      if (aboutIndex[v] >= 0 && surface.parts[v] == FacePart::Skin)
        coverage[size_t(aboutIndex[v])] = std::max(coverage[size_t(aboutIndex[v])], c);
  }
  return coverage;
}

}  // namespace

BrowBand findBrows(const eng::Model& face, const PosedFace& posed, const FaceSurface& surface,
                   const FaceLandmarks& landmarks) {
  BrowBand band;
  band.coverage.assign(surface.positions.size(), 0.0f);
  const LandmarkFrame frame(landmarks);
  const float span = frame.eyeSpan();
  auto plane = [&](const glm::vec3& p) {
    return glm::vec2(glm::dot(p - frame.origin(), frame.side()), glm::dot(p - frame.origin(), frame.up())) / span;
  };
  const SkinColour colour(face, posed, surface);

  // The subject's right brow (17-21) over its upper lid (36-39), the left (22-26) over 42-45.
  constexpr std::array<std::array<size_t, 2>, 2> kBrow{{{17, 21}, {22, 26}}};
  constexpr std::array<std::array<size_t, 2>, 2> kLid{{{36, 39}, {42, 45}}};
  for (size_t b = 0; b < 2; ++b) {
    BrowBand::Brow& brow = band.brows[b];
    std::vector<glm::vec2> line, lid;
    float depthOfLine = 0.0f;  // the brow line's mean depth along forward, eye spans
    for (size_t i = kBrow[b][0]; i <= kBrow[b][1]; ++i) {
      line.push_back(plane(landmarks.points[i]));
      depthOfLine += glm::dot(landmarks.points[i] - frame.origin(), frame.forward()) / span / 5.0f;
    }
    for (size_t i = kLid[b][0]; i <= kLid[b][1]; ++i) lid.push_back(plane(landmarks.points[i]));
    auto bySide = [](const glm::vec2& a, const glm::vec2& c) { return a.x < c.x; };
    std::sort(line.begin(), line.end(), bySide);
    std::sort(lid.begin(), lid.end(), bySide);
    const float from = line.front().x - kPastEnds, to = line.back().x + kPastEnds;

    std::vector<float> forehead;
    for (size_t v = 0; v < surface.positions.size(); ++v) {
      const glm::vec2 q = plane(surface.positions[v]);
      if (q.x < from || q.x > to) continue;
      // The face's front only: not the hair's or the head's back.
      if (glm::dot(surface.positions[v] - frame.origin(), frame.forward()) / span < depthOfLine - 0.3f) continue;
      const float top = heightAt(line, q.x);
      if (surface.parts[v] == FacePart::Skin && q.y > top + kForeheadFrom && q.y < top + kForeheadTo)
        if (const std::optional<float> light = colour.at(v)) forehead.push_back(*light);
      if (q.y > heightAt(lid, q.x) + kOverLid && q.y < top + kOverLine &&
          (surface.parts[v] == FacePart::Brows || surface.parts[v] == FacePart::Skin)) {
        brow.about.push_back(v);
        brow.place.push_back(q);
      }
    }
    const float reference = forehead.size() >= kMinCovered ? median(forehead) : 0.0f;
    const std::vector<float> coverage = paintedCoverage(brow, surface, colour, reference, plane, line, lid);
    std::vector<float> depths;
    for (size_t i = 0; i < brow.about.size(); ++i) {
      if (coverage[i] <= 0.0f) continue;
      band.coverage[brow.about[i]] = coverage[i];
      brow.covered.push_back(brow.about[i]);
      brow.coveredAt.push_back(i);
      if (coverage[i] >= 0.5f) depths.push_back(heightAt(line, brow.place[i].x) - brow.place[i].y);
    }
    const float reach = depths.size() >= kMinCovered ? *std::max_element(depths.begin(), depths.end()) : 0.0f;
    if (!(reach > 0.0f) || reach > kMaxReach) {
      for (size_t v : brow.covered) band.coverage[v] = 0.0f;
      brow = {};
      continue;
    }
    brow.reach = reach;
  }
  return band;
}

void moveAsOnePiece(const BrowBand& band, const glm::vec3& up, std::span<glm::vec3> deltas) {
  for (const BrowBand::Brow& brow : band.brows) {
    std::vector<glm::vec3> moved(brow.covered.size());
    for (size_t c = 0; c < brow.covered.size(); ++c) {
      const size_t i = brow.coveredAt[c];
      glm::vec3 best = deltas[brow.covered[c]];
      for (size_t j = 0; j < brow.about.size(); ++j)
        if (std::abs(brow.place[j].x - brow.place[i].x) < kAlongBrow && brow.place[j].y >= brow.place[i].y &&
            glm::dot(deltas[brow.about[j]], up) > glm::dot(best, up))
          best = deltas[brow.about[j]];
      moved[c] = glm::mix(deltas[brow.covered[c]], best, std::min(1.0f, 2.0f * band.coverage[brow.covered[c]]));
    }
    for (size_t c = 0; c < brow.covered.size(); ++c) deltas[brow.covered[c]] = moved[c];
  }
}

}  // namespace autorig
