#include "bake/gltf_timeline.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/core/name_index.h"
#include "engine/core/work_counter.h"
#include "facial/runtime/json/json_document.h"  // formatNumber

namespace bake {
namespace {

facial::KeyInterpolation keyInterpolation(eng::Interpolation interpolation) {
  switch (interpolation) {
    case eng::Interpolation::Step: return facial::KeyInterpolation::Step;
    case eng::Interpolation::Linear: return facial::KeyInterpolation::Linear;
    case eng::Interpolation::CubicSpline: return facial::KeyInterpolation::Hermite;
  }
  return facial::KeyInterpolation::Linear;
}

std::string animationLabel(const eng::Model& model, size_t animation) {
  const std::string& name = model.animations[animation].name;
  return "animation " + std::to_string(animation) + (name.empty() ? "" : " '" + name + "'");
}

}  // namespace

eng::Result<facial::Timeline> importGltfTimeline(const eng::Model& model, size_t animation, std::vector<std::string>* warnings) {
  if (animation >= model.animations.size())
    return eng::makeError(eng::ErrorKind::NotFound, "animation " + std::to_string(animation) + " out of range (" +
                          std::to_string(model.animations.size()) + " animations)");
  const eng::Animation& source = model.animations[animation];
  const std::string label = animationLabel(model, animation);
  facial::Timeline timeline;
  timeline.channels = facial::TimelineChannels::Targets;  // glTF animates the mesh's own targets
  timeline.name = source.name.empty() ? "animation" + std::to_string(animation) : source.name;
  std::vector<facial::Keyframe> keys;
  // Targets already animated, hashed: a scan of the tracks per target was
  // quadratic in a file with many targets.
  eng::NameIndex animated;
  for (size_t c = 0; c < source.channels.size(); ++c) {
    const eng::WeightsChannel& channel = source.channels[c];
    const std::string where = label + " channel " + std::to_string(c);
    if (channel.mesh < 0 || static_cast<size_t>(channel.mesh) >= model.meshes.size())
      return eng::makeError(eng::ErrorKind::Malformed, where + ": mesh " + std::to_string(channel.mesh) + " out of range (" +
                            std::to_string(model.meshes.size()) + " meshes)");
    const eng::Mesh& mesh = model.meshes[channel.mesh];
    if (channel.targetCount != mesh.targetNames.size())
      return eng::makeError(eng::ErrorKind::Malformed, where + ": " + std::to_string(channel.targetCount) + " weights per key, mesh '" +
                            mesh.name + "' has " + std::to_string(mesh.targetNames.size()) + " targets");
    const bool cubic = channel.interpolation == eng::Interpolation::CubicSpline;
    const size_t perKey = channel.targetCount * (cubic ? 3 : 1);
    if (channel.values.size() != channel.times.size() * perKey)
      return eng::makeError(eng::ErrorKind::Malformed, where + ": " + std::to_string(channel.values.size()) + " values for " +
                            std::to_string(channel.times.size()) + " keys of " + std::to_string(perKey));
    for (size_t k = 1; k < channel.times.size(); ++k)
      if (!(channel.times[k] > channel.times[k - 1]))
        return eng::makeError(eng::ErrorKind::Malformed, where + ": key " + std::to_string(k) + " time " + facial::formatNumber(channel.times[k]) +
                              " is not after the previous one (glTF requires strictly increasing times)");
    if (!channel.times.empty() && channel.times.front() < 0.0f)
      return eng::makeError(eng::ErrorKind::Malformed, where + ": negative key time " + facial::formatNumber(channel.times.front()));
    for (size_t t = 0; t < channel.targetCount; ++t) {
      const std::string& target = mesh.targetNames[t];
      if (animated.find(target)) {
        if (warnings) warnings->push_back(where + ": target '" + target + "' is already animated by an earlier channel; kept the first");
        continue;
      }
      keys.clear();
      eng::countWork(channel.times.size());
      for (size_t k = 0; k < channel.times.size(); ++k) {
        facial::Keyframe key{.time = channel.times[k], .interpolation = keyInterpolation(channel.interpolation)};
        const size_t base = k * perKey;
        if (cubic) {
          key.inTangent = channel.values[base + t];
          key.value = channel.values[base + channel.targetCount + t];
          key.outTangent = channel.values[base + 2 * channel.targetCount + t];
        } else {
          key.value = channel.values[base + t];
        }
        keys.push_back(key);
      }
      if (keys.empty()) continue;
      timeline.addTrack(target, keys);
      animated.add(target, static_cast<uint32_t>(timeline.tracks.size() - 1));
    }
  }
  if (timeline.tracks.empty()) return eng::makeError(eng::ErrorKind::Malformed, label + " animates no morph weights");
  timeline.duration = timeline.lastKeyTime();
  if (timeline.duration <= 0.0f) return eng::makeError(eng::ErrorKind::Malformed, label + " lasts 0 s (all keys at time 0)");
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed(label + ": ");
  return timeline;
}

eng::Result<ImportedTimelines> importGltfTimelines(const eng::Model& model) {
  ImportedTimelines out;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    if (model.animations[a].channels.empty()) continue;
    auto timeline = importGltfTimeline(model, a, &out.warnings);
    if (!timeline) return timeline.error();
    out.timelines.push_back(std::move(timeline).value());
  }
  return out;
}

namespace {

// Slope of a track just before (left) or after (right) `time`; 0 where it holds.
float trackSlope(std::span<const facial::Keyframe> keys, float time, bool left) {
  if (keys.size() < 2) return 0.0f;
  if (left ? time <= keys.front().time : time >= keys.back().time) return 0.0f;
  if (left ? time > keys.back().time : time < keys.front().time) return 0.0f;
  uint32_t segment = findSegment(keys, time);
  if (left && segment > 0 && time == keys[segment].time) --segment;  // the segment ending here
  return segmentDerivative(keys[segment], keys[segment + 1], time);
}

// A mesh's target names, hashed: looked up once per track (a search of the
// names per track was quadratic in a face with many targets).
eng::NameIndex targetIndex(const eng::Mesh& mesh) {
  eng::NameIndex index;
  index.reserve(mesh.targetNames.size());
  for (size_t t = 0; t < mesh.targetNames.size(); ++t) index.add(mesh.targetNames[t], static_cast<uint32_t>(t));
  return index;
}

// A face file often holds several meshes (head, eyes, teeth): the first node
// whose mesh has a target for every track, else the first node with a mesh
// (-1 when none has one). Each mesh is checked once, however many nodes draw it.
int nodeForTimeline(const eng::Model& model, const facial::Timeline& timeline) {
  int firstMeshNode = -1;
  std::map<int, bool> coversEveryTrack;  // by mesh
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const int m = model.nodes[n].mesh;
    if (m < 0 || static_cast<size_t>(m) >= model.meshes.size()) continue;
    if (firstMeshNode < 0) firstMeshNode = static_cast<int>(n);
    const auto [covers, fresh] = coversEveryTrack.try_emplace(m, false);
    if (fresh) {
      const eng::NameIndex names = targetIndex(model.meshes[m]);
      covers->second = std::all_of(timeline.tracks.begin(), timeline.tracks.end(),
                                   [&](const facial::TimelineTrack& track) { return names.find(track.channel).has_value(); });
    }
    if (covers->second) return static_cast<int>(n);
  }
  return firstMeshNode;
}

// The track animating each of the mesh's targets, or -1. Errors: a track
// whose channel is not one of the mesh's targets.
eng::Result<std::vector<int>> trackOfEachTarget(const eng::Mesh& mesh, const facial::Timeline& timeline, int node) {
  std::vector<int> trackOfTarget(mesh.targetNames.size(), -1);
  const eng::NameIndex names = targetIndex(mesh);
  for (size_t i = 0; i < timeline.tracks.size(); ++i) {
    const std::optional<uint32_t> target = names.find(timeline.tracks[i].channel);
    if (!target)
      return eng::makeError(eng::ErrorKind::NotFound, "timeline '" + timeline.name + "' animates '" + timeline.tracks[i].channel +
                            "', which is not a morph target of mesh '" + mesh.name + "' (node " + std::to_string(node) +
                            ", " + std::to_string(mesh.targetNames.size()) + " targets)");
    trackOfTarget[*target] = static_cast<int>(i);
  }
  return trackOfTarget;
}

// The glTF key times and the one interpolation all targets share.
struct ExportKeys {
  std::vector<float> times;
  eng::Interpolation interpolation = eng::Interpolation::Linear;
};

// All-step or all-linear timelines keep their own keys and mode; any other
// mix becomes cubic spline, with extra keys inside cosine segments (at
// sampleRate) and a short ramp before each step, which a spline cannot jump.
eng::Result<ExportKeys> exportKeys(const facial::Timeline& timeline, size_t targets, const GltfTimelineExport& options) {
  bool allStep = true, allLinear = true;
  size_t count = 2;  // the keys at 0 and at the duration
  for (size_t i = 0; i < timeline.tracks.size(); ++i) {
    const std::span<const facial::Keyframe> keys = timeline.trackKeys(i);
    count += keys.size();
    for (size_t k = 0; k + 1 < keys.size(); ++k) {  // the last key's mode shapes no segment
      allStep = allStep && keys[k].interpolation == facial::KeyInterpolation::Step;
      allLinear = allLinear && keys[k].interpolation == facial::KeyInterpolation::Linear;
    }
  }
  const bool cubic = !allStep && !allLinear;
  // A cosine segment of hours at sampleRate is millions of keys from a few
  // bytes of timeline: counted (in double, no overflow) and charged, with the
  // weights of every target at each, before any is made.
  if (cubic)
    for (size_t i = 0; i < timeline.tracks.size(); ++i) {
      const std::span<const facial::Keyframe> keys = timeline.trackKeys(i);
      for (size_t k = 0; k + 1 < keys.size(); ++k)
        if (keys[k].interpolation == facial::KeyInterpolation::Cosine)
          count += static_cast<size_t>(std::min(1e15, std::ceil(double(keys[k + 1].time - keys[k].time) * options.sampleRate)));
        else if (keys[k].interpolation == facial::KeyInterpolation::Step)
          ++count;
    }
  eng::LoadBudget budget(options.maxBytes);
  if (auto ok = budget.charge(count, sizeof(float) * (1 + targets * (cubic ? 3 : 1)),
                              std::to_string(count) + " glTF keys of " + std::to_string(targets) + " targets");
      !ok)
    return ok.error().prefixed("timeline '" + timeline.name + "': ");
  std::vector<float> times;
  times.reserve(count);
  for (size_t i = 0; i < timeline.tracks.size(); ++i)
    for (const facial::Keyframe& key : timeline.trackKeys(i)) times.push_back(key.time);
  if (cubic) {
    for (size_t i = 0; i < timeline.tracks.size(); ++i) {
      const std::span<const facial::Keyframe> keys = timeline.trackKeys(i);
      for (size_t k = 0; k + 1 < keys.size(); ++k) {
        const float start = keys[k].time, end = keys[k + 1].time;
        if (keys[k].interpolation == facial::KeyInterpolation::Cosine) {
          const int pieces = std::max(1, static_cast<int>(std::ceil((end - start) * options.sampleRate)));
          for (int p = 1; p < pieces; ++p) times.push_back(start + (end - start) * static_cast<float>(p) / pieces);
        } else if (keys[k].interpolation == facial::KeyInterpolation::Step && keys[k].value != keys[k + 1].value) {
          times.push_back(end - std::min(options.stepRamp, 0.5f * (end - start)));
        }
      }
    }
  }
  // glTF has no duration of its own (an animation ends at its last key): a
  // key at 0 and one at the timeline's end keep its holds at both ends.
  times.push_back(0.0f);
  times.push_back(timeline.duration);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return ExportKeys{std::move(times), allStep    ? eng::Interpolation::Step
                                      : allLinear ? eng::Interpolation::Linear
                                                  : eng::Interpolation::CubicSpline};
}

// Every target's weight at each key time (untracked targets hold their
// default weight); for cubic splines with the in- and out-slopes around it.
void sampleWeights(eng::WeightsChannel& channel, const eng::Mesh& mesh, const facial::Timeline& timeline,
                   const std::vector<int>& trackOfTarget) {
  const size_t targets = channel.targetCount;
  const bool cubic = channel.interpolation == eng::Interpolation::CubicSpline;
  channel.values.reserve(channel.times.size() * targets * (cubic ? 3 : 1));
  auto emit = [&](auto&& perTarget) {
    for (size_t t = 0; t < targets; ++t) channel.values.push_back(perTarget(t));
  };
  for (float time : channel.times) {
    auto value = [&](size_t t) {
      const int track = trackOfTarget[t];
      if (track < 0) return t < mesh.defaultWeights.size() ? mesh.defaultWeights[t] : 0.0f;
      return facial::sampleKeys(timeline.trackKeys(static_cast<size_t>(track)), time);
    };
    auto slope = [&](bool left) {
      return [&, left](size_t t) {
        const int track = trackOfTarget[t];
        return track < 0 ? 0.0f : trackSlope(timeline.trackKeys(static_cast<size_t>(track)), time, left);
      };
    };
    if (cubic) emit(slope(true));
    emit(value);
    if (cubic) emit(slope(false));
  }
}

}  // namespace

eng::Result<void> exportGltfTimeline(eng::Model& model, const facial::Timeline& timeline, const GltfTimelineExport& options) {
  if (auto valid = timeline.validate(); !valid) return valid.error().prefixed("timeline '" + timeline.name + "': ");
  const int node = options.node >= 0 ? options.node : nodeForTimeline(model, timeline);
  if (node < 0 || static_cast<size_t>(node) >= model.nodes.size() || model.nodes[node].mesh < 0 ||
      static_cast<size_t>(model.nodes[node].mesh) >= model.meshes.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "timeline '" + timeline.name + "': node " + std::to_string(node) +
                          " does not exist or has no mesh (" + std::to_string(model.nodes.size()) + " nodes)");
  if (!(options.sampleRate > 0.0f) || !(options.stepRamp > 0.0f))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "timeline export: sampleRate and stepRamp must be > 0");
  const int meshIndex = model.nodes[node].mesh;
  const eng::Mesh& mesh = model.meshes[meshIndex];
  eng::Result<std::vector<int>> trackOfTarget = trackOfEachTarget(mesh, timeline, node);
  if (!trackOfTarget) return trackOfTarget.error();

  eng::Result<ExportKeys> keys = exportKeys(timeline, mesh.targetNames.size(), options);
  if (!keys) return keys.error();
  eng::WeightsChannel channel;
  channel.node = node;
  channel.mesh = meshIndex;
  channel.targetCount = mesh.targetNames.size();
  channel.interpolation = keys->interpolation;
  channel.times = std::move(keys->times);
  sampleWeights(channel, mesh, timeline, *trackOfTarget);
  model.animations.push_back(eng::Animation{timeline.name, {std::move(channel)}});
  return {};
}

}  // namespace bake
