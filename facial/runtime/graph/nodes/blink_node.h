#pragma once
// Procedural blinking on top of an input pose ("procedural life").
//
// Timing: the gap between blinks is uniform in [minInterval, maxInterval]
// (seeded RNG per character, so runs repeat exactly); a blink closes in
// closeDuration, holds closedDuration, and opens in the slower openDuration
// (lids fall faster than they rise), each phase cosine-eased so the lid
// speed is continuous at its ends; with probability doubleBlinkChance a
// second blink follows after doubleBlinkGap.
//
// Amount on each blink channel c, with b(t) in [0,1] the blink curve:
//   out[c] = in[c] + (1 - in[c]) * b(t) * amplitude
//   amplitude = amount * (1 - smoothstep(wideStart, wideFull, wide))
//                      * (1 - blockLane) * (1 - blendLane)
// so a blink always closes the lid fully from wherever the expression holds
// it, and is suppressed while the eyes are widened (wide = the largest input
// weight of the eye-widening channels, AU5 by default). The lanes carry VRM's
// overrideBlink of the expressions on screen, weighted by how much they show:
// "blend" scales blinking by 1 - weight; "block" does the same and also keeps
// new blinks from starting while any of it shows. Fading instead of cutting
// the blink keeps even an expression change mid-blink free of pops.
//
// JSON (graph_json.h): "blink": input, channels, wideChannels, amount, minInterval, maxInterval, closeDuration,
//            closedDuration, openDuration, doubleBlinkChance, doubleBlinkGap, wideStart, wideFull
#include <optional>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/graph/node_types.h"
#include "facial/runtime/graph/parameters.h"
#include "engine/core/result.h"

namespace facial {

class JsonNode;
namespace detail {
class NodeReader;
}  // namespace detail

struct BlinkNode {
  static constexpr std::string_view kType = "blink";  // JSON "type"
  // The graph file reader's hook (detail/node_reader.h): reads this node's JSON object.
  static eng::Result<BlinkNode> read(const JsonNode& j, detail::NodeReader& r);

  NodeIndex input = kNoNode;
  std::vector<std::string> channels;      // blink channels; empty: the AU45 channels of the graph
  std::vector<std::string> wideChannels;  // eye widening; empty: AU5 when the graph has it
  FloatInput amount = FloatInput::fixed(1.0f);
  float minInterval = 2.0f, maxInterval = 6.0f;  // seconds between blinks
  float closeDuration = 0.06f;
  float closedDuration = 0.02f;
  float openDuration = 0.10f;
  float doubleBlinkChance = 0.1f;
  float doubleBlinkGap = 0.08f;  // open -> next close
  float wideStart = 0.35f, wideFull = 0.85f;

  // Derived at build.
  std::vector<uint32_t> channelIndices, wideIndices;

  enum class Phase : uint8_t { Open, Closing, Closed, Opening };
  struct State {
    std::minstd_rand rng;
    Phase phase = Phase::Open;
    float phaseTime = 0;   // seconds into the phase
    float waitTime = 2;    // Open phase: seconds until the next blink starts
    bool secondOfDouble = false;  // the coming blink is the second of a double
  };

  // Blink curve b in [0,1] for a phase and the time spent in it.
  float curve(Phase phase, float phaseTime) const;
  // Largest |db/dt| (per second): pi/2 over the shorter eased phase.
  float maxRate() const;

  static constexpr uint32_t kScratchPoses = 0;
  void inputs(std::vector<NodeIndex>& out) const { out.push_back(input); }
  eng::Result<void> prepare(const BuildContext& ctx);
  State makeState(const GraphDefinition& definition, NodeIndex self, uint64_t seed) const;
  void reset(State& state) const;
  void evaluate(EvalContext& ctx, NodeIndex self, std::span<float> out) const;

 private:
  float drawInterval(State& state) const;
  void advance(State& state, float dt, bool mayStart) const;
};

}  // namespace facial
