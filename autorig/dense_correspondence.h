#pragma once
// Dense correspondence between the source face's skin and the target's,
// grown from the landmarks: the source skin is warped onto the target
// (autorig/landmark_warp.h), well-spread target vertices find their closest
// points on it and join the landmarks as control points, the warp is solved
// again; then every target vertex takes its closest point on the warped
// source (a triangle and barycentrics), never across a closing line (upper
// lip to upper lip, upper lid to upper lid).
#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/closest_point.h"
#include "autorig/face_frame.h"
#include "autorig/face_landmarks.h"
#include "autorig/face_parts.h"
#include "autorig/landmark_warp.h"
#include "autorig/posed_face.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace autorig {

// Some parts of a face as one triangle soup in world space.
struct FaceSurface {
  struct VertexRef {
    uint32_t primitive = 0;  // index into PosedFace::primitives
    uint32_t vertex = 0;
  };
  std::vector<VertexRef> vertices;
  std::vector<FacePart> parts;       // per vertex
  std::vector<glm::vec3> positions;  // per vertex, world space at rest
  std::vector<std::array<uint32_t, 3>> triangles;  // into vertices; only triangles wholly of the parts
  // Per vertex, the first of its UV seam's copies (itself when it has none):
  // vertices of one primitive at one position with different UVs are one
  // point of the surface in two islands of its texture. Copies with the
  // same UVs are a split the author made (a slit mouth, a closed lid's
  // margins, a cut made to open them) and stay apart. Empty: no copies.
  std::vector<uint32_t> seamRoot;
  uint32_t rootOf(size_t v) const { return seamRoot.empty() ? uint32_t(v) : seamRoot[v]; }
};

// The vertices of `model` whose part is one of `wanted` (FaceParts order).
FaceSurface gatherSurface(const eng::Model& model, const PosedFace& posed, const FaceParts& parts,
                          std::initializer_list<FacePart> wanted);

// The vertices on the rim of an opening in the surface (an edge of one
// triangle only; UV seam copies count as their root, so a seam is no rim).
std::vector<char> openingRims(const FaceSurface& surface);

// Each vertex's region: by the landmarks' closing lines where it is clearly
// above or below one, and near a line by the mesh instead (the region of the
// nearest clearly labelled vertex along the surface's edges, a UV seam's
// copies as one), because the lips of a closed mouth and the lids of a
// closed eye meet there, often as separate vertices at the same places; a
// lip's rim at the mouth's slit by the side its triangles lie on.
std::vector<FaceRegion> labelRegions(const FaceSurface& surface, const LandmarkFrame& frame);

// `target` with each mouth corner's pair of points (outer 48 and inner 60,
// 54 and 64) spaced within kCornerSpacingTolerance of the mouth's width of
// the source's spacing (scaled by the mouth's width), about the pair's middle
// as found. The two lie about 0.04 eye spans apart, what dlib's points on a
// face it does not know are often off by, and the warp passes through the
// inner one and near the outer, so an inner corner found a little outside
// its outer one folds the skin between them (the built-in head under noise of
// 0.02 eye spans: 454 skin triangles about the mouth folded over six draws,
// 218 with the corners steadied). Pairs found within the tolerance stay.
FaceLandmarks withSteadyMouthCorners(const FaceLandmarks& source, const FaceLandmarks& target);

// The landmark pairs a warp from one face to another goes through. Landmarks
// that meet on the source (the inner lips of a closed mouth) are one control
// point, held by the first pair; closer than minSeparation, the RBF refuses them.
struct LandmarkPairs {
  std::vector<glm::vec3> source, target;
  std::vector<uint32_t> landmark;  // per pair, its landmark's index
  float minSeparation = 0.0f;  // world units of the source
};
LandmarkPairs distinctLandmarkPairs(const FaceLandmarks& source, const FaceLandmarks& target);

struct CorrespondenceOptions {
  int growthRounds = 2;       // warp, match, re-solve
  int maxGrownPairs = 300;    // control points added to the 68 landmarks
  float sampleSpacing = 0.09f;  // between grown pairs, in eye spans
  float maxGap = 0.25f;       // a target vertex farther than this (eye spans) from the warped source gets no match
};

struct Correspondence {
  LandmarkWarp warp;  // source -> target, landmarks and grown pairs
  size_t grownPairs = 0;
  std::vector<glm::vec3> warpedSource;  // the source surface's positions warped
  std::vector<ClosestPoint> matches;    // one per target vertex (found = false: none within maxGap)
  std::vector<FaceRegion> sourceRegions;  // labelRegions of the source
  std::vector<FaceRegion> targetRegions;  // and of the target
};

eng::Result<Correspondence> correspond(const FaceSurface& source, const FaceLandmarks& sourceLandmarks,
                                       const FaceSurface& target, const FaceLandmarks& targetLandmarks,
                                       const CorrespondenceOptions& options = {});

}  // namespace autorig
