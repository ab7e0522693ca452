#include "editor/glb_export.h"

#include <algorithm>
#include <cmath>

#include "bake/gltf_timeline.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_writer.h"

namespace editor {

namespace fs = std::filesystem;

namespace {

constexpr float kUnmoved = 1e-5f;  // weights this close to the default do not move

// Sample times: k / rate, and the clip's end.
std::vector<float> sampleTimes(float duration, float rate) {
  std::vector<float> times;
  const size_t steps = size_t(std::ceil(duration * rate - 1e-4f));
  for (size_t k = 0; k < steps; ++k) times.push_back(float(k) / rate);
  times.push_back(duration);
  return times;
}

int busiestMesh(const eng::WeightLayout& layout, const std::vector<bool>& moves) {
  int best = -1;
  size_t bestCount = 0;
  for (int m = 0; m < layout.meshCount(); ++m) {
    const size_t count = size_t(std::count(moves.begin() + layout.offset(m), moves.begin() + layout.offset(m + 1), true));
    if (count > bestCount) best = m, bestCount = count;
  }
  return best;
}

// The baked targets at the editor's weights as every mesh's default weights:
// the sculpt moves vertices of several meshes (teeth, eyes near the chin), and
// a clip animates one mesh only; the others show their defaults.
void holdBakedTargets(eng::Model& model, std::span<const std::pair<std::string, float>> held) {
  for (eng::Mesh& mesh : model.meshes)
    for (const auto& [name, weight] : held) {
      const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), name);
      if (it == mesh.targetNames.end()) continue;
      mesh.defaultWeights.resize(mesh.targetNames.size(), 0.0f);
      mesh.defaultWeights[size_t(it - mesh.targetNames.begin())] = weight;
    }
}

}  // namespace

eng::Result<SampledClip> sampleClipWeights(const TimelineDocument& clip, TimelinePose& pose, const eng::WeightLayout& layout,
                                           float sampleRate) {
  if (!(sampleRate > 0.0f) || !std::isfinite(sampleRate))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "export: sample rate " + std::to_string(sampleRate) + " must be > 0");
  const std::vector<float> times = sampleTimes(clip.duration(), sampleRate);
  const size_t total = layout.total();
  std::vector<float> base(total), weights(times.size() * total);
  if (auto rest = pose.pose(TimelineDocument(), 0.0f, base); !rest) return rest.error();
  std::vector<bool> moves(total, false);
  for (size_t s = 0; s < times.size(); ++s) {
    const std::span<float> row(weights.data() + s * total, total);
    if (auto posed = pose.pose(clip, times[s], row); !posed) return posed.error();
    for (size_t i = 0; i < total; ++i) moves[i] = moves[i] || std::abs(row[i] - base[i]) > kUnmoved;
  }
  SampledClip sampled;
  sampled.timeline.name = clip.name();
  sampled.timeline.duration = clip.duration();
  sampled.timeline.loop = clip.loop();
  sampled.mesh = busiestMesh(layout, moves);
  if (sampled.mesh < 0) return sampled;
  const std::vector<std::string> names = layout.names();
  std::vector<facial::Keyframe> keys(times.size());
  for (size_t i = 0; i < total; ++i) {
    if (!moves[i]) continue;
    if (i < layout.offset(sampled.mesh) || i >= layout.offset(sampled.mesh + 1)) {
      ++sampled.droppedTargets;
      continue;
    }
    for (size_t s = 0; s < times.size(); ++s) keys[s] = {.time = times[s], .value = weights[s * total + i]};
    sampled.timeline.addTrack(names[i], keys);
  }
  return sampled;
}

eng::Result<GlbExportSummary> exportGlb(eng::Model model, std::span<const TimelineDocument* const> clips, TimelinePose& pose,
                                        const eng::WeightLayout& layout, const fs::path& path, float sampleRate,
                                        std::span<const std::pair<std::string, float>> held) {
  GlbExportSummary summary;
  holdBakedTargets(model, held);
  for (const TimelineDocument* clip : clips) {
    auto sampled = sampleClipWeights(*clip, pose, layout, sampleRate);
    if (!sampled) return sampled.error().prefixed(path.string() + ": clip '" + clip->name() + "': ");
    summary.droppedTargets += sampled->droppedTargets;
    if (sampled->mesh < 0) continue;
    const auto node = std::find_if(model.nodes.begin(), model.nodes.end(), [&](const eng::Node& n) { return n.mesh == sampled->mesh; });
    if (node == model.nodes.end()) continue;  // a mesh no node draws is not shown either
    const std::vector<std::string>& meshTargets = model.meshes[size_t(sampled->mesh)].targetNames;
    for (const auto& [name, weight] : held)
      if (std::find(meshTargets.begin(), meshTargets.end(), name) != meshTargets.end() && !sampled->timeline.findTrack(name)) {
        const facial::Keyframe hold[] = {{.time = 0.0f, .value = weight}, {.time = clip->duration(), .value = weight}};
        sampled->timeline.addTrack(name, hold);
      }
    if (auto added = bake::exportGltfTimeline(model, sampled->timeline, {.node = int(node - model.nodes.begin())}); !added)
      return added.error().prefixed(path.string() + ": clip '" + clip->name() + "': ");
    ++summary.animations;
  }
  auto written = eng::writeFileWhole(path, [&](const fs::path& partial) { return eng::saveModel(model, partial); });
  if (!written) return written.error().prefixed(path.string() + ": not exported: ");  // the writer names the partial file
  return summary;
}

}  // namespace editor
