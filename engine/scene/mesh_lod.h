#pragma once
// Levels of detail of one triangle list: coarser index lists over the SAME
// vertices (meshopt_simplify collapses edges and keeps the vertex buffer), so
// morph targets, skin influences and every other per-vertex array stay valid
// for every level. Borders are locked: the openings of a face (eyes, mouth,
// nostrils), the neck's cut and the rims of separate parts keep their exact
// outline at every level; UV seams (vertices split at the same position) are
// kept by meshoptimizer itself.
//
// A CPU rasteriser (lavapipe) pays per triangle for set-up and binning and,
// worse, shades whole 4x4 blocks per triangle: a 71k-triangle head drawn at
// 832x520 covers a few pixels per triangle, so most of its fragment work is
// wasted on blocks the triangle hardly touches. A renderer picks the coarsest
// level whose error projects below a pixel (SceneRenderer's LodPolicy).
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

struct LodLevel {
  std::vector<uint32_t> indices;  // triangle list over the source vertices
  // How far the level may stray from the full mesh, in model units (the
  // simplifier's error, summed over the cascade that made it).
  float error = 0.0f;
};

struct LodChainOptions {
  // Lists with fewer triangles get no coarser level. Small parts count: the
  // built-in head's two 3k-triangle ears were a sixth of what a 512-px frame drew.
  uint32_t minTriangles = 1024;
  // Each level aims at this fraction of the previous one's triangles...
  float ratio = 0.5f;
  // ...and is kept only if it has at most `keepBelow` of them (else
  // simplification stalled: locked borders, seams, a tiny part).
  float keepBelow = 0.8f;
  // Relative to the mesh's extent: no level strays further than this.
  float maxRelativeError = 0.02f;
  uint32_t maxLevels = 6;  // coarser levels, besides the full list
};

// The coarser levels of `indices` (a triangle list over `positions`, every
// index < positions.size()), finest first, each with fewer triangles and a
// larger error than the one before; empty when the list is too small or
// does not simplify. Positions are the rest pose.
//
// Triangles flagged in `keep` (one flag per triangle, or empty: none) are in
// every level as they are (keptTriangles); the rest simplifies with the
// outline it shares with them locked, so no crack opens between them.
std::vector<LodLevel> buildLodChain(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                    const LodChainOptions& options = {}, std::span<const uint8_t> keep = {});

struct Image;
struct Primitive;
// What the simplifier cannot see, so a level keeps it as it is. It measures
// how far the surface moves, not how far the picture painted on it slides
// (the built-in head's lash lines wandered at half a pixel) nor how a crease
// it flattens is lit (a dark spot at the inner corner of an eye, where the
// flattened skin fell into the eyeball's shadow).
struct KeptTriangleLimits {
  // Painted: the largest channel range (0..1) of a triangle's base-colour
  // texels or corner colours. Skin grain stays under it; lash lines, brows,
  // lip edges and irises go over.
  float paintedContrast = 0.15f;
  // Creased: the largest angle between two of a triangle's corner normals.
  float creaseDegrees = 30.0f;
};
// One flag per triangle of `indices`: 1 where the base-colour texture (read
// through `texcoords`, wrapping; may be null) or the vertex colours vary
// more than `limits.paintedContrast` within it, or its corner normals turn
// more than `limits.creaseDegrees`. Arrays not one per vertex are ignored.
std::vector<uint8_t> keptTriangles(std::span<const uint32_t> indices, std::span<const glm::vec2> texcoords,
                                   const Image* texture, std::span<const glm::vec4> colors,
                                   std::span<const glm::vec3> normals, size_t vertexCount,
                                   const KeptTriangleLimits& limits = {});
// A primitive's: its painted triangles (base colour `texture`, may be null,
// and vertex colours) and its creases at rest and in each target's pose (the
// levels are made at rest, where a fold a target makes -- a stretched mouth
// corner -- is smooth skin).
std::vector<uint8_t> keptTriangles(const Primitive& prim, const Image* texture, const KeptTriangleLimits& limits = {});

}  // namespace eng
