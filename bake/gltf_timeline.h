#pragma once
// glTF `weights` animations <-> timelines over a mesh's morph target names.
//
// Import: each animation becomes one Timeline with a track per morph target
// (named like the target). STEP keys import as Step, LINEAR as Linear,
// CUBICSPLINE as Hermite with the glTF in/out tangents (both are d weight /
// d second, scaled by the key gap when evaluated, so the curve is the same).
//
// Export: a timeline becomes one glTF animation on a node's mesh. glTF keys
// all targets of a channel at shared times with one interpolation, so keys
// go to the union of the tracks' key times and the interpolation is chosen
// to keep the curve:
//   every segment Step   -> STEP          (exact)
//   every segment Linear -> LINEAR        (exact)
//   otherwise            -> CUBICSPLINE   value plus left/right derivatives at every key time:
//     exact for Linear and Hermite segments (a cubic piece is fixed by its end values and slopes);
//     Cosine segments are split at `sampleRate` and match to ~1e-4 at 30 Hz;
//     a Step inside a mixed timeline holds, then ramps in the last `stepRamp` seconds.
// Keys are also written at 0 and at the timeline's duration, so a hold at
// either end survives (a glTF animation ends at its last key). When no node
// is named, the first node whose mesh has a target for every track is used.
// Targets without a track hold the mesh's default weight. Loop modes have no
// glTF equivalent and are not written.
#include <string>
#include <vector>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/graph/timeline.h"

namespace bake {

struct ImportedTimelines {
  std::vector<facial::Timeline> timelines;    // one per animation with weights channels, in file order
  std::vector<std::string> warnings;  // e.g. a target name animated on two meshes (the first kept)
};

// Animation `animation` of `model` as a timeline. Fails (naming the animation
// and channel) on inconsistent channel data, unsorted key times, or an
// animation with no weights channel or no duration.
eng::Result<facial::Timeline> importGltfTimeline(const eng::Model& model, size_t animation,
                                         std::vector<std::string>* warnings = nullptr);
// Every animation that has weights channels.
eng::Result<ImportedTimelines> importGltfTimelines(const eng::Model& model);

struct GltfTimelineExport {
  int node = -1;            // node whose mesh's weights are animated; -1: the first node with a mesh
  float sampleRate = 30.0f; // keys per second inside Cosine segments (CUBICSPLINE export)
  float stepRamp = 1e-3f;   // seconds a Step takes inside a CUBICSPLINE export
  // The keys' times and values are charged to this budget before they are
  // made (a long cosine segment at sampleRate is millions of keys).
  size_t maxBytes = eng::kDefaultLoadBudgetBytes;
};

// Appends `timeline` to model.animations as an animation named like it.
// Fails when the node has no mesh or a track names no target of that mesh.
eng::Result<void> exportGltfTimeline(eng::Model& model, const facial::Timeline& timeline, const GltfTimelineExport& options = {});

}  // namespace bake
