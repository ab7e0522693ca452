#include "facial/runtime/character/gaze_rig.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include <glm/glm.hpp>

namespace facial {
namespace {

constexpr uint32_t kNone = UINT32_MAX;

// "blendShape1.eyeLookIn_L" -> "eyelookinl": no prefix, no '_', lower case.
std::string normalisedTargetName(std::string_view name) {
  if (const size_t dot = name.rfind('.'); dot != std::string_view::npos) name.remove_prefix(dot + 1);
  std::string out;
  out.reserve(name.size());
  for (char c : name)
    if (c != '_') out.push_back(char(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

// The FACS gaze unit a target name starts with (61..64), or 0: "AU61", "AU61_EyesTurnLeft",
// "au63 eyes up"; not "AU610" nor "AU6".
int facsGazeUnit(std::string_view name) {
  if (const size_t slash = name.rfind('/'); slash != std::string_view::npos) name.remove_prefix(slash + 1);
  if (name.size() < 4 || std::tolower(static_cast<unsigned char>(name[0])) != 'a' ||
      std::tolower(static_cast<unsigned char>(name[1])) != 'u' || name[2] != '6' || name[3] < '1' || name[3] > '4')
    return 0;
  if (name.size() > 4 && std::isdigit(static_cast<unsigned char>(name[4]))) return 0;
  return 60 + (name[3] - '0');
}

float degrees(float radians) { return glm::degrees(radians); }

void add(std::span<float> weights, uint32_t target, float amount) {
  if (target == kNone || amount <= 0.0f) return;
  weights[target] = std::clamp(weights[target] + amount, 0.0f, 1.0f);
}

}  // namespace

GazeRig GazeRig::create(std::span<const std::string> targetNames, const VrmExpressionSet* vrm) {
  GazeRig rig;
  rig.targetCount_ = static_cast<uint32_t>(targetNames.size());
  rig.arkit_.fill(kNone);
  rig.facs_.fill(kNone);
  static constexpr const char* kArkitDirections[] = {"in", "out", "up", "down"};
  static constexpr const char* kSides[][2] = {{"left", "l"}, {"right", "r"}};
  for (uint32_t i = 0; i < targetNames.size(); ++i) {
    const std::string name = normalisedTargetName(targetNames[i]);
    for (int side = 0; side < 2; ++side)
      for (int d = 0; d < 4; ++d)
        for (const char* suffix : kSides[side])
          if (name == std::string("eyelook") + kArkitDirections[d] + suffix) rig.arkit_[size_t(side * 4 + d)] = i;
    // AU61 eyes left, AU62 right, AU63 up, AU64 down: Direction order.
    if (const int unit = facsGazeUnit(targetNames[i]); unit && rig.facs_[size_t(unit - 61)] == kNone)
      rig.facs_[size_t(unit - 61)] = i;
  }
  // ARKit gaze is all eight shapes or none: half a set would look cross-eyed.
  rig.hasArkit_ = std::find(rig.arkit_.begin(), rig.arkit_.end(), kNone) == rig.arkit_.end();
  if (!rig.hasArkit_) rig.arkit_.fill(kNone);

  if (vrm && vrm->lookAt.type == VrmLookAtType::Expression && vrm->targetCount() == targetNames.size()) {
    static constexpr std::string_view kVrmNames[] = {"lookleft", "lookright", "lookup", "lookdown"};
    for (const VrmExpression& e : vrm->expressions) {
      if (e.group != VrmProceduralGroup::LookAt || e.bindCount == 0) continue;
      std::string lower;
      for (char c : e.name) lower.push_back(char(std::tolower(static_cast<unsigned char>(c))));
      for (int d = 0; d < kDirections; ++d) {
        if (lower != kVrmNames[d] || !rig.vrmBinds_[size_t(d)].empty()) continue;
        rig.vrmBinds_[size_t(d)].assign(vrm->binds.begin() + e.firstBind, vrm->binds.begin() + e.firstBind + e.bindCount);
        ++rig.vrmDirections_;
      }
    }
    // Expressions move both eyes together: the outer range serves left and right (as three-vrm does).
    rig.vrmRanges_ = {vrm->lookAt.horizontalOuter, vrm->lookAt.horizontalOuter, vrm->lookAt.verticalUp,
                      vrm->lookAt.verticalDown};
  }
  return rig;
}

bool GazeRig::hasFacs() const {
  return std::any_of(facs_.begin(), facs_.end(), [](uint32_t t) { return t != kNone; });
}

std::string GazeRig::describe() const {
  std::string text;
  if (hasArkit()) text += "ARKit eyeLook*";
  if (hasFacs()) text += std::string(text.empty() ? "" : ", ") + "FACS AU61-64";
  if (hasVrmExpressions()) text += std::string(text.empty() ? "" : ", ") + "VRM lookAt expressions";
  return text.empty() ? "none" : text;
}

eng::Result<void> GazeRig::apply(EyeGaze left, EyeGaze right, std::span<float> weights) const {
  if (weights.size() != targetCount_)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "gaze: " + std::to_string(weights.size()) + " weights given, the rig was made for " +
                          std::to_string(targetCount_) + " targets");
  for (float a : {left.yaw, left.pitch, right.yaw, right.pitch})
    if (!std::isfinite(a)) return eng::makeError(eng::ErrorKind::InvalidArgument, "gaze: an eye angle is not finite");

  if (hasArkit_) {
    // +yaw (toward the face's left, +X): the left eye looks out, the right eye in.
    const auto perEye = [&](const EyeGaze& g, ArkitSlot in, ArkitSlot out, ArkitSlot up, ArkitSlot down, float outSign) {
      const float side = degrees(g.yaw) * outSign / kArkitLookDegrees;
      const float vertical = degrees(g.pitch) / kArkitLookDegrees;
      add(weights, arkit_[out], std::max(side, 0.0f));
      add(weights, arkit_[in], std::max(-side, 0.0f));
      add(weights, arkit_[up], std::max(vertical, 0.0f));
      add(weights, arkit_[down], std::max(-vertical, 0.0f));
    };
    perEye(left, InLeft, OutLeft, UpLeft, DownLeft, 1.0f);
    perEye(right, InRight, OutRight, UpRight, DownRight, -1.0f);
  }
  const float yaw = degrees(0.5f * (left.yaw + right.yaw)), pitch = degrees(0.5f * (left.pitch + right.pitch));
  add(weights, facs_[LookLeft], std::max(yaw, 0.0f) / kFacsLookDegrees);
  add(weights, facs_[LookRight], std::max(-yaw, 0.0f) / kFacsLookDegrees);
  add(weights, facs_[LookUp], std::max(pitch, 0.0f) / kFacsLookDegrees);
  add(weights, facs_[LookDown], std::max(-pitch, 0.0f) / kFacsLookDegrees);
  if (vrmDirections_ > 0) {
    const std::array<float, kDirections> angle{std::max(yaw, 0.0f), std::max(-yaw, 0.0f), std::max(pitch, 0.0f),
                                               std::max(-pitch, 0.0f)};
    for (int d = 0; d < kDirections; ++d) {
      const float w = std::clamp(vrmRanges_[size_t(d)].map(angle[size_t(d)]), 0.0f, 1.0f);
      for (const VrmMorphBind& bind : vrmBinds_[size_t(d)])
        if (bind.target < weights.size()) add(weights, bind.target, w * bind.weight);
    }
  }
  return {};
}

}  // namespace facial
