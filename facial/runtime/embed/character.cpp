#include "facial/character.h"

#include <cmath>
#include <optional>
#include <set>
#include <vector>

#include "facial/runtime/character/face_driver.h"
#include "facial/runtime/character/gaze_rig.h"
#include "facial/runtime/graph/graph_json.h"
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
  std::string scheme = "target names";
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

}  // namespace

Character::Character(std::unique_ptr<State> state) : state_(std::move(state)) {}
Character::Character(Character&&) noexcept = default;
Character& Character::operator=(Character&&) noexcept = default;
Character::~Character() = default;

eng::Result<Character> Character::create(const std::filesystem::path& graphFile, std::span<const std::string> targetNames,
                                         const CharacterOptions& options) {
  auto state = std::make_unique<State>();
  state->targetNames.assign(targetNames.begin(), targetNames.end());
  std::set<std::string_view> seen;
  for (const std::string& name : state->targetNames)
    if (name.empty() || !seen.insert(name).second)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "character: target name '" + name + "' is " + (name.empty() ? "empty" : "given twice"));

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
  auto driver = FaceDriver::create(*graph, state->graphRig ? &*state->graphRig : nullptr, state->targetNames, rest,
                                   options.seed);
  if (!driver) return rigError && !state->graphRig ? *rigError : driver.error().prefixed(graphFile.string() + ": ");
  state->driver.emplace(std::move(*driver));

  auto life = CharacterLife::create({.seed = options.seed, .sway = options.idleLife, .saccades = options.idleLife});
  if (!life) return life.error();
  state->life.emplace(std::move(*life));
  state->gaze = GazeRig::create(state->targetNames);
  state->weights = rest;
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

eng::Result<void> Character::lookAt(float x, float y, float z) { return state_->life->lookAt({x, y, z}); }

void Character::lookAhead() { state_->life->lookAhead(); }

eng::Result<void> Character::update(float dt) {
  if (!(dt >= 0.0f) || !std::isfinite(dt))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "update: dt " + std::to_string(dt) + " is not a finite number of seconds >= 0");
  state_->driver->update(dt);
  state_->life->update(dt);
  const std::span<const float> driven = state_->driver->targetWeights();
  std::copy(driven.begin(), driven.end(), state_->weights.begin());
  // Sizes match by construction and the angles are finite (clamped), so this cannot fail.
  return state_->gaze.apply(state_->life->eyeGaze(Eye::Left), state_->life->eyeGaze(Eye::Right), state_->weights);
}

std::span<const float> Character::weights() const { return state_->weights; }
uint32_t Character::weightCount() const { return static_cast<uint32_t>(state_->weights.size()); }
std::array<float, 4> Character::headRotation() const { return xyzw(state_->life->headRotation()); }
std::array<float, 4> Character::eyeRotation(Eye eye) const { return xyzw(state_->life->eyeRotation(eye)); }
float Character::breathLift() const { return state_->life->breathLift(); }
std::string_view Character::rigScheme() const { return state_->scheme; }
std::string Character::gazeOutputs() const { return state_->gaze.describe(); }

}  // namespace facial
