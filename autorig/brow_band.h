#pragma once
// A face's brows, painted on its skin or modelled as a part of their own,
// found between the landmarks' brow line (dlib puts points 17-26 on a
// brow's upper edge) and the upper lids: which skin vertices a brow covers
// (darker than the forehead above it in the skin's colour).
//
// Raised, a brow moves as one piece: its hairs do not stretch, the lid's
// skin below does. The built-in head's raised brows keep their full lift a
// brow's width under the brow line, and its brows are thin and set high;
// carried onto a face with heavy brows set low (Ready Player Me's cover the
// upper 58% of the way from lid to brow line, the head's 37%), their lower
// edge sat where the head's lid skin stretches and rose half as far as the
// upper: the brows' triangles grew to 1.41 times their area (1.11 now) and
// surprise drew the brows as thick black bars. So in the units that raise
// the brows (autorig/target_transfer), each vertex a brow covers takes the
// motion of the vertex beside it that rises most, from its own height to
// just over the brow line. Lowered, the lid's skin under a brow cannot fold
// on a coarse mesh, so AU4 is left as carried.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "autorig/dense_correspondence.h"
#include "autorig/face_landmarks.h"
#include "autorig/posed_face.h"
#include "engine/scene/model.h"

namespace autorig {

struct BrowBand {
  std::vector<float> coverage;  // per surface vertex: how much a brow covers it, 0..1
  // Per brow (the subject's right, left): the vertices it covers, those
  // about it (across its length, from the upper lid to over the brow line),
  // and each vertex's place in the face plane (side, up; eye spans). A
  // vertex is covered as far as the darkest of its triangles is brow: on a
  // coarse mesh a brow's edge crosses triangles whose corners lie above and
  // below it, and they rise whole.
  struct Brow {
    std::vector<size_t> covered, about;
    std::vector<glm::vec2> place;  // per `about` entry
    std::vector<size_t> coveredAt;  // per `covered` entry: its index in `about`
    float reach = 0.0f;  // how far under the line the mostly covered vertices go, eye spans; 0: none found
  };
  std::array<Brow, 2> brows;
  bool found() const { return brows[0].reach > 0.0f || brows[1].reach > 0.0f; }
};

// Faces without a texture, or brows no darker than the forehead (fair
// brows, a fringe over the forehead), find none.
BrowBand findBrows(const eng::Model& face, const PosedFace& posed, const FaceSurface& surface,
                   const FaceLandmarks& landmarks);

// Raised, a brow moves as one piece: each covered vertex's displacement
// (surface order, `up` the face's) goes, as far as it is covered, to that of
// the vertex within kAlongBrow eye spans of it along the brow, at or above
// it, that rises most.
inline constexpr float kAlongBrow = 0.05f;
void moveAsOnePiece(const BrowBand& band, const glm::vec3& up, std::span<glm::vec3> deltas);

}  // namespace autorig
