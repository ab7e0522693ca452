#pragma once
// The built-in head in transfer tests: loaded, set up as the source, and a
// way to compare two targets vertex by vertex.
#include <optional>
#include <span>

#include "autorig/target_transfer.h"
#include "engine/scene/model.h"
#include "tests/common/test_meshes.h"

namespace transfer_fixture {

// data/head.glb, or nullopt (with a test failure) when it cannot be read.
std::optional<eng::Model> loadHead();
// autorig::builtInSource, a test failure when it fails; `head` must outlive it.
autorig::SourceFace headSource(const eng::Model& head);

// Transfers for tests of the made shapes: the detail layers (tested in
// detail_transfer_test.cpp) are a third of a transfer's time and change no shape.
inline constexpr autorig::TransferOptions kShapesOnly{.detailLayers = false};

// The model without any morph target (nor the animations that weight them): a face to rig.
using testing_support::stripped;

// `face` (posed at rest) rigged from the built-in head with the landmarks of
// tests/autorig/data/<landmarksFile> and the parts finder; nullopt, with a
// test failure, when a step fails. `landmarks` (optional) receives them.
std::optional<autorig::TransferResult> rigWithFixtureLandmarks(const eng::Model& face, const autorig::PosedFace& posed,
                                                              const char* landmarksFile,
                                                              autorig::FaceLandmarks* landmarks = nullptr,
                                                              const autorig::TransferOptions& options = {});

// The gap between an eye's lids with `target` at 1, over the gap at rest, along
// the face's up: the skin vertices of mesh m nearest the upper lid landmarks
// against those nearest the lower ones (each side's mean); below zero the
// upper lid passed the lower. NaN, with a test failure, without the target.
float lidGap(const eng::Model& model, size_t m, const autorig::PosedFace& posed, const autorig::FaceLandmarks& landmarks,
             const char* target, std::span<const size_t> upper, std::span<const size_t> lower);

// How far target B of b is from target A of a on one primitive of the mesh
// named `mesh` (same vertices): the largest vertex difference over A's
// largest displacement, |a - b|max / |a|max.
float relativeError(const eng::Model& a, const eng::Model& b, const char* mesh, size_t primitive, const char* targetA,
                    const char* targetB);

// A made target against a true one over every vertex of one mesh (all its
// primitives), in the true target's own units:
//   relativeRms = sqrt(sum |made - true|^2 / sum |true|^2)  (0: the same; 1: as far as no motion)
//   cosine      = sum made.true / sqrt(sum |made|^2 sum |true|^2)  (direction agreement)
//   gain        = sum made.true / sum |true|^2  (how much of the true motion is made)
struct Comparison {
  float relativeRms = 0.0f;
  float cosine = 0.0f;
  float gain = 0.0f;
};
// Errors (a test failure and infinities) when a target is missing.
Comparison compareTargets(const eng::Mesh& made, const char* madeName, const eng::Mesh& truth, const char* trueName);

}  // namespace transfer_fixture
