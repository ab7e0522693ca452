#pragma once
// The embedding API (C++): one animated character an engine drives with its
// own meshes. A character is an animation graph (a JSON graph file, see
// facial/runtime/graph/graph_json.h) played over the engine's list of morph
// target names: the rig scheme is detected from the names (ARKit 52, FACS
// action units, CANDIDE-3, whole-expression names) or given by a rig map file,
// and the character's idle life (sway, breathing, saccades) and gaze are added.
// Every frame: set parameters and triggers, update(dt), read weights() (one
// per target name, in the order given) and the head / eye rotations for a
// skinned avatar's joints. Errors are values (eng::Result; error().kind says
// what went wrong, e.g. NotFound for a missing file or an unknown parameter,
// InvalidArgument for a broken precondition; error().message is one line
// naming the file and the problem); no function throws. The C API
// (facial/c_api.h) wraps this class and adds error codes.
//
//   auto character = facial::Character::create("tour.json", names, {.expressions = "expressions.json"});
//   character->trigger("happy");
//   character->update(1.0f / 60.0f);
//   for (size_t i = 0; i < names.size(); ++i) mesh.setWeight(i, character->weights()[i]);
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/result.h"
#include "facial/runtime/character/character_life.h"

namespace facial {

class GraphDefinition;  // facial/runtime/graph/graph_definition.h
using SharedGraphDefinition = std::shared_ptr<const GraphDefinition>;
class RigMapping;              // facial/runtime/rig/rig_mapping.h
struct VrmExpressionSet;       // facial/runtime/rig/vrm_expressions.h
class VisemeTrack;             // facial/runtime/speech/viseme_track.h

// For an engine that has already loaded the graph and built the rig (our
// programs' face loader does, VRM expressions included): create() takes
// these instead of files. Everything is copied; nothing needs to outlive the call.
struct CharacterParts {
  SharedGraphDefinition graph;
  const RigMapping* rig = nullptr;        // the rig the graph drives; null: a graph over target names
  std::span<const float> restWeights;     // one per target name (the model's defaults); empty: all 0
  const VrmExpressionSet* vrm = nullptr;  // a VRM model's lookAt expressions steer the eyes too
};

struct CharacterOptions {
  // The expression presets the graph's pose nodes name (the project's
  // data/expressions.json); empty: none, for graphs over raw target names.
  std::filesystem::path expressions;
  // A rig map file naming which targets are which action unit or emotion
  // (data/rigmaps/README.md); empty: detected from the target names.
  std::filesystem::path rigmap;
  uint64_t seed = 0;      // blink and saccade streams, sway phases
  bool idleLife = true;   // head sway, breathing and saccades (the graph's blinks stay)
  // The character will speak (speak()): create() fails, in one line naming the
  // model's target count and what was looked for, when nothing on its rig
  // moves the mouth.
  bool speaks = false;
  // Eye centres in head space (+X the face's left), where lookAt() aims from.
  std::array<float, 3> leftEye{0.032f, 0.0f, 0.0f};
  std::array<float, 3> rightEye{-0.032f, 0.0f, 0.0f};
};

class Character {
 public:
  // Errors: the graph, presets or rig map cannot be read, the names match no
  // rig scheme while the graph speaks action units, an empty or duplicate
  // target name, a graph channel that is no target (graphs over target names).
  static eng::Result<Character> create(const std::filesystem::path& graphFile, std::span<const std::string> targetNames,
                                       const CharacterOptions& options = {});
  // From a loaded graph and rig (options.expressions and options.rigmap are
  // not read). targetNames are the names the rig was built over; a name may
  // repeat (a model's flat list has one per mesh that has the target).
  // Errors: no graph, rest weights that are not one per target name, the
  // graph's channels do not fit the rig or the names.
  static eng::Result<Character> create(const CharacterParts& parts, std::span<const std::string> targetNames,
                                       const CharacterOptions& options = {});
  Character(Character&&) noexcept;
  Character& operator=(Character&&) noexcept;
  ~Character();

  // Graph parameters by name. Errors (nothing changes): no parameter of that name and type (the message lists the graph's parameters).
  eng::Result<void> setFloat(std::string_view parameter, float value);
  eng::Result<void> setBool(std::string_view parameter, bool value);
  eng::Result<void> trigger(std::string_view parameter);
  // Takes back a trigger no transition has consumed yet (a UI where the last press wins).
  eng::Result<void> resetTrigger(std::string_view parameter);
  // The current state of a state machine node of the graph, by node name
  // (empty: the graph's first state machine); none when there is no such node.
  std::optional<std::string_view> currentState(std::string_view machineNode = {}) const;
  // The same machine in more detail: how long the character has been in the
  // state and whether a transition into it is still blending (a tool that
  // captures each state once it has settled).
  struct MachineStatus {
    std::string_view state;
    float secondsInState = 0.0f;
    bool blending = false;
  };
  std::optional<MachineStatus> machineStatus(std::string_view machineNode = {}) const;

  // Where the eyes look, in head space (+X the face's left, +Y up, +Z out of
  // the face, origin between the eyes, metres). Errors: a non-finite coordinate.
  eng::Result<void> lookAt(float x, float y, float z);
  void lookAhead();

  // A pose that takes over from the graph by `amount` (0: the graph alone,
  // 1: the pose alone; the gaze is added on top either way) from the next
  // update() on, for a UI that poses the face while the graph runs on below.
  // targetWeights: one per target name; expressionWeights: one per VRM
  // expression of the rig (expressionWeights().size(), may be empty). Errors
  // (nothing changes): other sizes, an amount outside [0, 1].
  eng::Result<void> overridePose(std::span<const float> targetWeights, std::span<const float> expressionWeights,
                                 float amount);

  // Lip sync: the track plays from the next update() on, sampled at the time
  // of setSpeechTime() (the host's audio clock, seconds from the track's 0;
  // 0 until set). Speech owns the mouth while it speaks; the graph's emotion
  // keeps the brows, eyes, cheeks and head and a share of the smile or frown
  // (docs/speech.md, "Speaking with an emotion"). A graph with a speech node
  // layers it itself. No allocation per frame. Errors (nothing changes): no
  // track or an empty one, a rig that cannot speak (nothing moves the mouth,
  // or a graph over raw target names), a non-finite time.
  eng::Result<void> speak(std::shared_ptr<const VisemeTrack> track);
  eng::Result<void> setSpeechTime(float audioClockSeconds);
  void stopSpeaking();
  bool speaking() const;

  // Advances by dt seconds and refreshes every output. Errors (nothing
  // changes): a negative or non-finite dt.
  eng::Result<void> update(float dt);

  // One weight per target name given to create(), in that order.
  std::span<const float> weights() const;
  uint32_t weightCount() const;
  // The rig's VRM expression weights (what a VRM's material binds follow), in
  // the rig's expression order; empty unless the rig maps VRM expressions.
  std::span<const float> expressionWeights() const;
  // Rotations as quaternions {x, y, z, w} in head-space axes: the idle sway for
  // the head joint, and each eye's gaze (from looking along +Z) for eye joints.
  std::array<float, 4> headRotation() const;
  std::array<float, 4> eyeRotation(Eye eye) const;
  // Chest lift of the breath, a fraction of the character's height.
  float breathLift() const;
  // The detected rig scheme ("ARKit 52", "action units", ...) and what the gaze drives.
  std::string_view rigScheme() const;
  std::string gazeOutputs() const;

 private:
  struct State;
  explicit Character(std::unique_ptr<State> state);
  static eng::Result<void> start(State& state, const SharedGraphDefinition& graph, std::span<const float> rest,
                                 const VrmExpressionSet* vrm, const CharacterOptions& options);
  std::unique_ptr<State> state_;
};

}  // namespace facial
