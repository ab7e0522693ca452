#pragma once
// File > Export .glb: the face with its sculpted (baked) targets and every
// clip as a glTF weights animation, in one file any glTF player opens (three.js,
// Blender, `facial timeline import` + `facial play`).
//
// A clip may key rig channels (action units, emotions) that a glTF player
// knows nothing of, so each clip is first turned into what the editor shows
// for it: the model's target weights (TimelinePose), sampled `sampleRate`
// times a second as LINEAR keys (plus one at the clip's end) on every target
// that leaves its default weight. glTF animates one mesh's weights per node,
// so the clip goes on the mesh with the most moving targets; targets of other
// meshes that move are counted in droppedTargets. The glTF writing itself is
// bake/gltf_timeline (exportGltfTimeline).
#include <filesystem>
#include <span>
#include <vector>

#include "editor/timeline_document.h"
#include "editor/timeline_pose.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "engine/scene/weights.h"
#include "facial/runtime/graph/timeline.h"

namespace editor {

inline constexpr float kGlbExportSampleRate = 30.0f;

struct SampledClip {
  facial::Timeline timeline;  // tracks named like the model's targets, LINEAR keys
  int mesh = -1;              // the mesh whose targets it animates (-1: nothing moves)
  size_t droppedTargets = 0;  // moving targets of other meshes
};

// `pose` poses `layout`'s model (the face as loaded); sampleRate > 0.
eng::Result<SampledClip> sampleClipWeights(const TimelineDocument& clip, TimelinePose& pose, const eng::WeightLayout& layout,
                                           float sampleRate = kGlbExportSampleRate);

struct GlbExportSummary {
  size_t animations = 0;      // clips written (a clip where nothing moves is left out)
  size_t droppedTargets = 0;  // over every clip
};

// Appends every clip to `model` (the face with its baked targets: it has
// every target of `layout` by name) as an animation named like the clip and
// writes it to `path` whole (nothing half-written on failure). `held`:
// targets of the model outside `layout` (the baked ones) and the weight the
// editor shows them at, held over every clip (a glTF weights animation sets
// every target of its mesh, so they must be in it).
eng::Result<GlbExportSummary> exportGlb(eng::Model model, std::span<const TimelineDocument* const> clips, TimelinePose& pose,
                                        const eng::WeightLayout& layout, const std::filesystem::path& path,
                                        float sampleRate = kGlbExportSampleRate,
                                        std::span<const std::pair<std::string, float>> held = {});

}  // namespace editor
