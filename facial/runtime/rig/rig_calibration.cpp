#include "facial/runtime/rig/rig_calibration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "facial/runtime/rig/action_units.h"

namespace facial {
namespace {

// The reach a full action unit should have, as a fraction of the face size
// (the extent of the region the rig's targets move, about brow-to-chin):
// how far its most-moved vertex travels in a clearly readable, prototypical
// expression of an adult face -- brows a little under a centimetre for 1/2/4,
// lip corners about one for 12 and 15, the chin a couple of centimetres for a
// relaxed jaw drop (26). Side channels (_L/_R) share their unit's reach.
struct Reference {
  int facsNumber;
  float reach;
};
constexpr std::array kActionUnitReach = {
    Reference{1, 0.055f},  Reference{2, 0.060f},  Reference{4, 0.050f},  Reference{5, 0.025f},
    Reference{6, 0.040f},  Reference{7, 0.023f},  Reference{9, 0.035f},  Reference{10, 0.045f},
    Reference{12, 0.090f}, Reference{15, 0.050f}, Reference{16, 0.040f}, Reference{17, 0.040f},
    Reference{20, 0.060f}, Reference{23, 0.022f}, Reference{24, 0.030f}, Reference{25, 0.040f},
    Reference{26, 0.120f},
};

}  // namespace

float referenceReach(std::string_view channel) {
  const auto index = actionUnitIndex(channel);
  if (!index) return 0.0f;
  const int number = actionUnits()[*index].facsNumber;
  for (const Reference& r : kActionUnitReach)
    if (r.facsNumber == number) return r.reach;
  return 0.0f;
}

std::string RigCalibration::summary() const {
  std::string out;
  char line[160];
  for (const ActionUnitCalibration& u : units) {
    std::snprintf(line, sizeof line, "  %-26s reach %.3f of the face, reference %.3f -> x%.2f\n", u.channel.c_str(),
                  u.reach, u.reference, u.scale);
    out += line;
  }
  return out;
}

eng::Result<RigCalibration> calibrateRig(const RigMapping& rig, std::span<const float> targetReach,
                                         const RigCalibrationOptions& options) {
  // An expression stage's rows drive whole expressions its author tuned
  // (VRM), not morph targets: they are left as they are.
  if (rig.expressionStage()) return RigCalibration{rig, {}};
  if (targetReach.size() != rig.targetCount())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "rig calibration: " + std::to_string(targetReach.size()) + " target reaches for " +
                          std::to_string(rig.targetCount()) + " targets");
  for (float r : targetReach)
    if (!std::isfinite(r) || r < 0.0f) return eng::makeError(eng::ErrorKind::Malformed, "rig calibration: a target reach is not a finite number >= 0");
  if (!(options.minScale > 0.0f) || !(options.maxScale >= options.minScale) || !std::isfinite(options.maxScale))
    return eng::makeError(eng::ErrorKind::Malformed, "rig calibration: the scale bounds must satisfy 0 < min <= max");
  const auto units = actionUnits();
  std::vector<float> overrideScale(units.size(), 1.0f);
  for (const auto& [channel, scale] : options.overrides) {
    const auto index = actionUnitIndex(channel);
    if (!index) return eng::makeError(eng::ErrorKind::Malformed, "rig calibration: '" + channel + "' is no action unit channel");
    if (!std::isfinite(scale) || scale < 0.0f)
      return eng::makeError(eng::ErrorKind::Malformed, "rig calibration: the scale of '" + channel + "' must be a finite number >= 0");
    overrideScale[*index] *= scale;
  }
  // A file's own statement: a name no channel has, or a scale that is no
  // number >= 0, is left out with a note (the file still loads).
  std::vector<float> givenScale(units.size(), -1.0f);  // < 0: measured
  std::vector<std::string> ignored;
  for (const auto& [channel, scale] : options.given) {
    const auto index = actionUnitIndex(channel);
    if (index && std::isfinite(scale) && scale >= 0.0f) givenScale[*index] = scale;
    else ignored.push_back(channel);
  }

  RigCalibration result;
  RigMappingBuilder builder = RigMappingBuilder::startingFrom(rig, /*withRows=*/false);
  for (uint32_t input = 0; input < rigInputCount(); ++input) {
    const auto targets = rig.targets(input);
    const auto gains = rig.gains(input);
    float scale = 1.0f;
    if (input < units.size() && !targets.empty()) {
      ActionUnitCalibration unit;
      unit.channel = std::string(units[input].name);
      unit.reference = referenceReach(unit.channel);
      for (size_t i = 0; i < targets.size(); ++i)
        unit.reach = std::max(unit.reach, std::abs(gains[i]) * targetReach[targets[i]]);
      if (givenScale[input] >= 0.0f)
        unit.scale = givenScale[input];
      else if (unit.reference > 0.0f && unit.reach > 0.0f)
        unit.scale = std::clamp(unit.reference / unit.reach, options.minScale, options.maxScale);
      unit.scale *= overrideScale[input];
      scale = unit.scale;
      result.units.push_back(std::move(unit));
    }
    for (size_t i = 0; i < targets.size(); ++i) builder.add(input, targets[i], gains[i] * scale);
  }
  bool calibrated = false;
  for (const ActionUnitCalibration& u : result.units) calibrated |= std::abs(u.scale - 1.0f) > 1e-3f;
  if (calibrated) builder.note("action-unit strengths calibrated to the face's size (facial rig --calibration lists them)");
  if (const auto given = std::count_if(givenScale.begin(), givenScale.end(), [](float g) { return g >= 0.0f; }); given > 0)
    builder.note(std::to_string(given) + " of them as the file states (facialCalibration: a face rigged by facial autorig keeps the built-in head's)");
  if (!ignored.empty()) {
    std::string line = "facialCalibration: " + std::to_string(ignored.size()) + " entries name no action unit channel or no scale >= 0, ignored:";
    for (const std::string& name : ignored) line += " " + name;
    builder.note(line);
  }
  auto built = builder.build();
  if (!built) return built.error();
  result.rig = std::move(*built);
  return result;
}

}  // namespace facial
