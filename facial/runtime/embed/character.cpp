#include "facial/character.h"

#include <cmath>
#include <optional>
#include <set>
#include <vector>

#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/character/gaze_rig.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/graph/preset_lookup.h"
#include "facial/runtime/rig/action_unit_rig.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

// Everything a character owns; behind a pointer so the driver's rig pointer stays valid on moves.
struct Character::State {
  std::vector<std::string> targetNames;
  std::optional<ExpressionLibrary> expressions;
  std::optional<RigMapping> rig;       // the detected / given rig (null: a graph over target names)
  std::optional<RigMapping> graphRig;  // the rig as an action-unit graph sees it (actionUnitRig)
  std::optional<FaceDriver> driver;
  std::optional<CharacterLife> life;
  GazeRig gaze;
  std::vector<float> weights;
  std::vector<float> expressionWeights;
  // overridePose(): the pose and how much of it replaces the graph's.
  std::vector<float> overrideWeights, overrideExpressions;
  float overrideAmount = 0.0f;
  std::string scheme = "target names";
  std::shared_ptr<const VisemeTrack> speech;  // what the driver samples; kept alive here
};

namespace {

std::array<float, 4> xyzw(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }

eng::Result<ParameterIndex> findParameter(const GraphDefinition& graph, std::string_view name, ParameterType type) {
  if (const auto index = graph.findParameter(name); index && graph.parameters()[*index].type == type) return *index;
  std::string list;
  for (const ParameterDecl& p : graph.parameters())
    list += (list.empty() ? "" : ", ") + p.name + " (" + std::string(parameterTypeName(p.type)) + ")";
  return eng::makeError(eng::ErrorKind::NotFound, "no " + std::string(parameterTypeName(type)) + " parameter '" + std::string(name) +
                        "' in the graph; it has: " + (list.empty() ? std::string("none") : list));
}

eng::Result<void> checkTargetNames(std::span<const std::string> names) {
  std::set<std::string_view> seen;
  for (const std::string& name : names)
    if (name.empty() || !seen.insert(name).second)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "character: target name '" + name + "' is " + (name.empty() ? "empty" : "given twice"));
  return {};
}

std::optional<NodeIndex> findStateMachine(const GraphDefinition& graph, std::string_view name) {
  if (!name.empty()) {
    const auto node = graph.findNode(name);
    return node && graph.nodeAs<StateMachineNode>(*node) ? node : std::nullopt;
  }
  for (NodeIndex n = 0; n < graph.nodes().size(); ++n)
    if (graph.nodeAs<StateMachineNode>(n)) return n;
  return std::nullopt;
}

// Whether the character's rig can carry speech, as one line when it cannot.
eng::Result<void> checkCanSpeak(const std::optional<RigMapping>& rig) {
  if (!rig)
    return eng::makeError(eng::ErrorKind::Unsupported, "character: cannot speak: the graph drives the model's target names "
                          "directly, with no rig to carry visemes (use a graph over action units)");
  if (!rig->speaks()) return eng::makeError(eng::ErrorKind::Unsupported, cannotSpeakMessage(*rig, "character"));
  return {};
}

}  // namespace

// What both create()s share once the graph and the rig are known: the driver, the idle life and the gaze.
eng::Result<void> Character::start(State& state, const SharedGraphDefinition& graph, std::span<const float> rest,
                                   const VrmExpressionSet* vrm, const CharacterOptions& options) {
  auto driver = FaceDriver::create(graph, state.graphRig ? &*state.graphRig : nullptr, state.targetNames, rest, options.seed);
  if (!driver) return driver.error();
  if (options.speaks) ENG_TRY(checkCanSpeak(state.graphRig));
  state.driver.emplace(std::move(*driver));
  CharacterLifeOptions lifeOptions{.seed = options.seed, .sway = options.idleLife, .saccades = options.idleLife};
  lifeOptions.leftEye = {options.leftEye[0], options.leftEye[1], options.leftEye[2]};
  lifeOptions.rightEye = {options.rightEye[0], options.rightEye[1], options.rightEye[2]};
  auto life = CharacterLife::create(lifeOptions);
  if (!life) return life.error();
  state.life.emplace(std::move(*life));
  state.gaze = GazeRig::create(state.targetNames, vrm);
  state.weights.assign(rest.begin(), rest.end());
  state.overrideWeights = state.weights;
  state.expressionWeights.assign(state.driver->expressionWeights().size(), 0.0f);
  state.overrideExpressions = state.expressionWeights;
  return {};
}

Character::Character(std::unique_ptr<State> state) : state_(std::move(state)) {}
Character::Character(Character&&) noexcept = default;
Character& Character::operator=(Character&&) noexcept = default;
Character::~Character() = default;

eng::Result<Character> Character::create(const std::filesystem::path& graphFile, std::span<const std::string> targetNames,
                                         const CharacterOptions& options) {
  if (auto names = checkTargetNames(targetNames); !names) return names.error();
  auto state = std::make_unique<State>();
  state->targetNames.assign(targetNames.begin(), targetNames.end());

  GraphLoadOptions load;
  if (!options.expressions.empty()) {
    auto expressions = ExpressionLibrary::load(options.expressions);
    if (!expressions) return expressions.error();
    state->expressions.emplace(std::move(*expressions));
    load.presets = presetLookup(*state->expressions);
  }
  auto graph = loadGraph(graphFile, load);
  if (!graph) return graph.error();

  // The rig is needed only by graphs over action units; its error is kept for them.
  std::optional<eng::Error> rigError;
  if (auto rig = buildRigMapping(state->targetNames, {.modelName = "character", .rigmapFile = options.rigmap}); rig) {
    state->scheme = rigSchemeName(rig->scheme());
    state->rig.emplace(std::move(*rig));
    if (state->expressions) {
      auto graphRig = actionUnitRig(*state->rig, *state->expressions);
      if (!graphRig) return graphRig.error().prefixed(graphFile.string() + ": ");
      state->graphRig.emplace(std::move(*graphRig));
    } else {
      state->graphRig = state->rig;
    }
  } else {
    rigError = rig.error();
  }
  const std::vector<float> rest(targetNames.size(), 0.0f);
  if (auto started = start(*state, *graph, rest, nullptr, options); !started) {
    if (!state->driver) return rigError && !state->graphRig ? *rigError : started.error().prefixed(graphFile.string() + ": ");
    return started.error();
  }
  return Character(std::move(state));
}

eng::Result<Character> Character::create(const CharacterParts& parts, std::span<const std::string> targetNames,
                                         const CharacterOptions& options) {
  if (!parts.graph) return eng::makeError(eng::ErrorKind::InvalidArgument, "character: no graph given");
  if (!parts.restWeights.empty() && parts.restWeights.size() != targetNames.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "character: " + std::to_string(parts.restWeights.size()) +
                          " rest weights for " + std::to_string(targetNames.size()) + " target names");
  auto state = std::make_unique<State>();
  state->targetNames.assign(targetNames.begin(), targetNames.end());
  if (parts.rig) {
    state->scheme = rigSchemeName(parts.rig->scheme());
    state->graphRig.emplace(*parts.rig);
  }
  const std::vector<float> zeros(targetNames.size(), 0.0f);
  const std::span<const float> rest = parts.restWeights.empty() ? std::span<const float>(zeros) : parts.restWeights;
  if (auto started = start(*state, parts.graph, rest, parts.vrm, options); !started) return started.error();
  return Character(std::move(state));
}

eng::Result<void> Character::setFloat(std::string_view parameter, float value) {
  auto index = findParameter(state_->driver->graph().definition(), parameter, ParameterType::Float);
  if (!index) return index.error();
  if (!std::isfinite(value)) return eng::makeError(eng::ErrorKind::InvalidArgument, "parameter '" + std::string(parameter) + "': value is not finite");
  state_->driver->graph().setFloat(*index, value);
  return {};
}

eng::Result<void> Character::setBool(std::string_view parameter, bool value) {
  auto index = findParameter(state_->driver->graph().definition(), parameter, ParameterType::Bool);
  if (!index) return index.error();
  state_->driver->graph().setBool(*index, value);
  return {};
}

eng::Result<void> Character::trigger(std::string_view parameter) {
  auto index = findParameter(state_->driver->graph().definition(), parameter, ParameterType::Trigger);
  if (!index) return index.error();
  state_->driver->graph().setTrigger(*index);
  return {};
}

eng::Result<void> Character::resetTrigger(std::string_view parameter) {
  auto index = findParameter(state_->driver->graph().definition(), parameter, ParameterType::Trigger);
  if (!index) return index.error();
  state_->driver->graph().resetTrigger(*index);
  return {};
}

std::optional<std::string_view> Character::currentState(std::string_view machineNode) const {
  const auto status = machineStatus(machineNode);
  if (!status) return std::nullopt;
  return status->state;
}

std::optional<Character::MachineStatus> Character::machineStatus(std::string_view machineNode) const {
  const GraphInstance& graph = state_->driver->graph();
  const auto node = findStateMachine(graph.definition(), machineNode);
  if (!node) return std::nullopt;
  const auto status = graph.stateMachineStatus(*node);
  const auto* machine = graph.definition().nodeAs<StateMachineNode>(*node);
  if (!status || status->current >= machine->states.size()) return std::nullopt;
  return MachineStatus{machine->states[status->current].name, status->stateTime, status->blending};
}

eng::Result<void> Character::overridePose(std::span<const float> targetWeights, std::span<const float> expressionWeights,
                                          float amount) {
  if (targetWeights.size() != state_->weights.size() || expressionWeights.size() != state_->expressionWeights.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "overridePose: " + std::to_string(targetWeights.size()) + " target and " +
                              std::to_string(expressionWeights.size()) + " expression weights for a character of " +
                              std::to_string(state_->weights.size()) + " and " +
                              std::to_string(state_->expressionWeights.size()));
  if (!(amount >= 0.0f && amount <= 1.0f))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "overridePose: amount " + std::to_string(amount) + " is not in [0, 1]");
  std::copy(targetWeights.begin(), targetWeights.end(), state_->overrideWeights.begin());
  std::copy(expressionWeights.begin(), expressionWeights.end(), state_->overrideExpressions.begin());
  state_->overrideAmount = amount;
  return {};
}

eng::Result<void> Character::lookAt(float x, float y, float z) { return state_->life->lookAt({x, y, z}); }

void Character::lookAhead() { state_->life->lookAhead(); }

eng::Result<void> Character::speak(std::shared_ptr<const VisemeTrack> track) {
  if (!track || track->keyCount() == 0)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "speak: no viseme track, or an empty one");
  ENG_TRY(checkCanSpeak(state_->graphRig));
  state_->driver->setSpeech(track.get(), 0.0f);
  state_->speech = std::move(track);
  return {};
}

eng::Result<void> Character::setSpeechTime(float audioClockSeconds) {
  if (!state_->driver->setSpeech(state_->speech.get(), audioClockSeconds))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "setSpeechTime: the time is not a finite number of seconds");
  return {};
}

void Character::stopSpeaking() {
  state_->driver->setSpeech(nullptr, 0.0f);
  state_->speech.reset();
}

bool Character::speaking() const { return state_->speech != nullptr; }

eng::Result<void> Character::update(float dt) {
  if (!(dt >= 0.0f) || !std::isfinite(dt))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "update: dt " + std::to_string(dt) + " is not a finite number of seconds >= 0");
  state_->driver->update(dt);
  state_->life->update(dt);
  const std::span<const float> driven = state_->driver->targetWeights();
  const std::span<const float> expressions = state_->driver->expressionWeights();
  const float amount = state_->overrideAmount;
  if (amount > 0.0f) {
    for (size_t t = 0; t < driven.size(); ++t)
      state_->weights[t] = driven[t] + amount * (state_->overrideWeights[t] - driven[t]);
    for (size_t e = 0; e < expressions.size(); ++e)
      state_->expressionWeights[e] = expressions[e] + amount * (state_->overrideExpressions[e] - expressions[e]);
  } else {
    std::copy(driven.begin(), driven.end(), state_->weights.begin());
    std::copy(expressions.begin(), expressions.end(), state_->expressionWeights.begin());
  }
  // Sizes match by construction and the angles are finite (clamped), so this cannot fail.
  return state_->gaze.apply(state_->life->eyeGaze(Eye::Left), state_->life->eyeGaze(Eye::Right), state_->weights);
}

std::span<const float> Character::weights() const { return state_->weights; }
std::span<const float> Character::expressionWeights() const { return state_->expressionWeights; }
uint32_t Character::weightCount() const { return static_cast<uint32_t>(state_->weights.size()); }
std::array<float, 4> Character::headRotation() const { return xyzw(state_->life->headRotation()); }
std::array<float, 4> Character::eyeRotation(Eye eye) const { return xyzw(state_->life->eyeRotation(eye)); }
float Character::breathLift() const { return state_->life->breathLift(); }
std::string_view Character::rigScheme() const { return state_->scheme; }
std::string Character::gazeOutputs() const { return state_->gaze.describe(); }

}  // namespace facial
