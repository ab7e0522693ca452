#include "facial/runtime/rig/action_unit_rig.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "facial/runtime/rig/action_units.h"

namespace facial {

eng::Result<RigMapping> actionUnitRig(const RigMapping& rig, const ExpressionLibrary& presets) {
  const uint32_t auCount = static_cast<uint32_t>(actionUnits().size());
  const std::span<const std::string_view> emotions = emotionNames();
  bool bindsEmotions = false;
  for (uint32_t e = 0; e < emotions.size(); ++e) bindsEmotions |= !rig.targets(emotionInput(Emotion(e))).empty();
  if (!bindsEmotions) return rig;

  // P: one column per basic emotion (neutral excluded), its preset at intensity 1.
  constexpr uint32_t kBasic = kEmotionCount - 1;
  Eigen::MatrixXd pattern = Eigen::MatrixXd::Zero(auCount, kBasic);
  std::vector<float> au(auCount);
  for (uint32_t k = 0; k < kBasic; ++k) {
    const std::string_view name = emotions[k + 1];
    const ExpressionPreset* preset = presets.find(name);
    if (!preset || preset->isCompound())
      return eng::makeError(eng::ErrorKind::Malformed, "the rig binds emotions, so the graph's action units are decoded through the basic "
                            "presets, but the presets have no basic '" + std::string(name) + "'");
    if (auto r = ExpressionLibrary::evaluate(*preset, 1.0f, au); !r) return r.error();
    for (uint32_t a = 0; a < auCount; ++a) pattern(a, k) = au[a];
  }
  const Eigen::MatrixXd gram = pattern.transpose() * pattern;
  const Eigen::LDLT<Eigen::MatrixXd> solver(gram);
  // Relative to the largest pivot: a preset that is (nearly) a mix of the others cannot be told apart.
  const Eigen::VectorXd pivots = solver.vectorD().cwiseAbs();
  if (solver.info() != Eigen::Success || pivots.minCoeff() <= 1e-9 * pivots.maxCoeff())
    return eng::makeError(eng::ErrorKind::Malformed, "the basic presets' action units are linearly dependent; emotion-level rig bindings "
                          "cannot be decoded from the graph's action units");
  const Eigen::MatrixXd decode = solver.solve(pattern.transpose());  // kBasic x auCount

  RigMappingBuilder builder = RigMappingBuilder::startingFrom(rig);
  for (uint32_t k = 0; k < kBasic; ++k) {
    const uint32_t emotion = emotionInput(Emotion(k + 1));
    const auto targets = rig.targets(emotion);
    const auto gains = rig.gains(emotion);
    for (uint32_t a = 0; a < auCount; ++a) {
      const double d = decode(k, a);
      if (std::abs(d) < 1e-6) continue;
      for (size_t i = 0; i < targets.size(); ++i) builder.add(a, targets[i], static_cast<float>(d * gains[i]));
    }
  }
  if (!rig.targets(emotionInput(Emotion::Neutral)).empty())
    builder.note("neutral: a target bound to the neutral emotion is not driven by action-unit graphs "
                 "(neutral has no action units to decode)");
  builder.note("emotion bindings are driven from the action units through the basic presets (least squares)");
  return builder.build();
}

}  // namespace facial
