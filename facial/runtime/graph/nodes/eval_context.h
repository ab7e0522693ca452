#pragma once
// Per-frame evaluation state handed down the node tree: the definition, the
// instance's parameters and node states, preallocated scratch poses and the
// time step. Nodes pull from their children through evaluate(); nothing here
// allocates.
#include <cassert>
#include <span>
#include <variant>
#include <vector>

#include "facial/runtime/graph/node.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/speech/viseme_track.h"

namespace facial {

// A stack of pose-sized buffers, sized at instantiate time from the
// definition's scratchPoseCount() (the deepest simultaneous need).
class ScratchStack {
 public:
  ScratchStack() = default;
  ScratchStack(uint32_t poseCount, uint32_t stride) : storage_(size_t{poseCount} * stride), stride_(stride) {}
  std::span<float> push() {
    assert((top_ + 1) * size_t{stride_} <= storage_.size() && "scratch pose count computed at build is too small");
    return std::span<float>(storage_).subspan(size_t{top_++} * stride_, stride_);
  }
  void pop() { --top_; }
  uint32_t capacity() const { return stride_ ? static_cast<uint32_t>(storage_.size() / stride_) : 0; }

 private:
  std::vector<float> storage_;
  uint32_t stride_ = 0;
  uint32_t top_ = 0;
};

// One scratch pose for the duration of a scope.
class ScratchPose {
 public:
  explicit ScratchPose(ScratchStack& stack) : stack_(stack), pose_(stack.push()) {}
  ~ScratchPose() { stack_.pop(); }
  ScratchPose(const ScratchPose&) = delete;
  ScratchPose& operator=(const ScratchPose&) = delete;
  std::span<float> pose() const { return pose_; }

 private:
  ScratchStack& stack_;
  std::span<float> pose_;
};

// The host's speech for this frame (GraphInstance::setSpeech): the track, the
// audio-clock time and the instance's sampling cursors. No track: silence.
struct SpeechInput {
  const VisemeTrack* track = nullptr;
  float time = 0;
  std::span<uint32_t> cursors;  // kSpeechChannelCount
};

struct EvalContext {
  const GraphDefinition& definition;
  std::span<float> parameters;
  std::span<NodeState> states;
  ScratchStack& scratch;
  float dt = 0;
  SpeechInput speech = {};

  // Advances `node` by dt and writes its pose (stride floats) to out.
  void evaluate(NodeIndex node, std::span<float> out);
  // out = sum of weights[i] * pose(inputs[i]) over the inputs with weight > 0;
  // inputs at weight 0 are not evaluated (so they do not advance). Uses one scratch pose.
  void evaluateWeightedSum(std::span<const NodeIndex> inputs, std::span<const float> weights, std::span<float> out);
  // Puts `node` and its subtree back to their initial state (state entry).
  void reset(NodeIndex node);

  float read(const FloatInput& input) const { return input.read(parameters); }
  template <class S>
  S& state(NodeIndex node) {
    S* s = std::get_if<S>(&states[node]);
    assert(s && "node state of the wrong type");
    return *s;
  }
};

}  // namespace facial
