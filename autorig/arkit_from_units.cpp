#include "autorig/arkit_from_units.h"

#include <algorithm>
#include <array>
#include <string_view>

#include <glm/gtx/compatibility.hpp>

#include "facial/runtime/rig/arkit_names.h"

namespace autorig {
namespace {

enum class Mask : unsigned char { All, Left, Right, UpperLip, LowerLip, LeftAwayFromLids, RightAwayFromLids };

struct Term {
  std::string_view unit;
  float gain = 1.0f;
  Mask mask = Mask::All;
};

struct Shape {
  std::string_view name;  // canonical ARKit
  std::array<Term, 2> terms;
};

// Half-widths of the masks' ramps, in eye spans: wide enough that the two
// halves of a unit meet without a crease, narrow enough that a lip's roll
// leaves the other lip.
constexpr float kMidlineRamp = 0.08f;
constexpr float kLipLineRamp = 0.03f;
// Away from the lids: none of a unit within kLidsNear eye spans of a lid
// line, all of it from kLidsFar.
constexpr float kLidsNear = 0.05f, kLidsFar = 0.12f;

// jawOpen at 1 is the jaw as far open as it goes: AU26 (the relaxed drop)
// and AU27 (the stretch beyond it) together, the sum arkit_scheme.cpp drives
// jawOpen with (0.6 + 0.4).
// AU26's share of jawOpen (arkit_scheme.cpp: AU26 drives jawOpen at 0.6).
constexpr float kJawDropShare = 0.6f;

constexpr std::array kShapes = {
    Shape{"browInnerUp", {Term{"AU1_InnerBrowRaiser"}}},
    Shape{"browDownLeft", {Term{"AU4_BrowLowerer", 1.0f, Mask::Left}}},
    Shape{"browDownRight", {Term{"AU4_BrowLowerer", 1.0f, Mask::Right}}},
    Shape{"browOuterUpLeft", {Term{"AU2_OuterBrowRaiser_L"}}},
    Shape{"browOuterUpRight", {Term{"AU2_OuterBrowRaiser_R"}}},
    // ARKit's cheekSquint raises the cheek; eyeSquint narrows the eye (AU6
    // does both, so a smile streamed with both closed the eyes twice over).
    Shape{"cheekSquintLeft", {Term{"AU6_CheekRaiser", 1.0f, Mask::LeftAwayFromLids}}},
    Shape{"cheekSquintRight", {Term{"AU6_CheekRaiser", 1.0f, Mask::RightAwayFromLids}}},
    Shape{"eyeBlinkLeft", {Term{"AU45_Blink_L"}}},
    Shape{"eyeBlinkRight", {Term{"AU45_Blink_R"}}},
    Shape{"eyeSquintLeft", {Term{"AU7_LidTightener", 1.0f, Mask::Left}}},
    Shape{"eyeSquintRight", {Term{"AU7_LidTightener", 1.0f, Mask::Right}}},
    Shape{"eyeWideLeft", {Term{"AU5_UpperLidRaiser", 1.0f, Mask::Left}}},
    Shape{"eyeWideRight", {Term{"AU5_UpperLidRaiser", 1.0f, Mask::Right}}},
    Shape{"jawOpen", {Term{"AU26_JawDrop"}, Term{"AU27_MouthStretch"}}},
    Shape{"mouthFrownLeft", {Term{"AU15_LipCornerDepressor", 1.0f, Mask::Left}}},
    Shape{"mouthFrownRight", {Term{"AU15_LipCornerDepressor", 1.0f, Mask::Right}}},
    Shape{"mouthFunnel", {Term{"AU22_LipFunneler"}}},
    Shape{"mouthPressLeft", {Term{"AU24_LipPressor", 1.0f, Mask::Left}, Term{"AU17_ChinRaiser", 1.0f, Mask::Left}}},
    Shape{"mouthPressRight", {Term{"AU24_LipPressor", 1.0f, Mask::Right}, Term{"AU17_ChinRaiser", 1.0f, Mask::Right}}},
    Shape{"mouthPucker", {Term{"AU18_LipPucker"}}},
    Shape{"mouthRollLower", {Term{"AU28_LipSuck", 1.0f, Mask::LowerLip}, Term{"AU17_ChinRaiser", 1.0f, Mask::LowerLip}}},
    Shape{"mouthRollUpper", {Term{"AU28_LipSuck", 1.0f, Mask::UpperLip}}},
    Shape{"mouthShrugLower", {Term{"AU17_ChinRaiser", 1.0f, Mask::LowerLip}}},
    Shape{"mouthSmileLeft", {Term{"AU12_LipCornerPuller_L"}}},
    Shape{"mouthSmileRight", {Term{"AU12_LipCornerPuller_R"}}},
    Shape{"mouthStretchLeft", {Term{"AU20_LipStretcher", 1.0f, Mask::Left}}},
    Shape{"mouthStretchRight", {Term{"AU20_LipStretcher", 1.0f, Mask::Right}}},
    Shape{"mouthUpperUpLeft", {Term{"AU10_UpperLipRaiser", 1.0f, Mask::Left}}},
    Shape{"mouthUpperUpRight", {Term{"AU10_UpperLipRaiser", 1.0f, Mask::Right}}},
    Shape{"noseSneerLeft", {Term{"AU9_NoseWrinkler", 1.0f, Mask::Left}}},
    Shape{"noseSneerRight", {Term{"AU9_NoseWrinkler", 1.0f, Mask::Right}}},
    Shape{"tongueOut", {Term{"AU19_TongueShow"}}},
};

float maskWeight(Mask mask, const glm::vec3& p, const LandmarkFrame& frame) {
  auto ramp = [](float x, float halfWidth) { return glm::smoothstep(-halfWidth, halfWidth, x); };
  switch (mask) {
    case Mask::All: return 1.0f;
    case Mask::Left: return leftHalf(p, frame);
    case Mask::Right: return 1.0f - leftHalf(p, frame);
    case Mask::UpperLip: return ramp(frame.aboveLipLine(p), kLipLineRamp);
    case Mask::LowerLip: return 1.0f - ramp(frame.aboveLipLine(p), kLipLineRamp);
    case Mask::LeftAwayFromLids:
    case Mask::RightAwayFromLids: {
      float margin = 0.0f;
      const FaceRegion region = frame.region(p, &margin);
      const bool nearLids = region != FaceRegion::None && region != FaceRegion::UpperLip && region != FaceRegion::LowerLip;
      const float away = nearLids ? glm::smoothstep(kLidsNear, kLidsFar, margin) : 1.0f;
      return away * (mask == Mask::LeftAwayFromLids ? leftHalf(p, frame) : 1.0f - leftHalf(p, frame));
    }
  }
  return 1.0f;
}


}  // namespace

float leftHalf(const glm::vec3& p, const LandmarkFrame& frame) {
  return glm::smoothstep(-kMidlineRamp, kMidlineRamp, frame.sideOf(p));
}

const NamedDeltas* findUnit(std::span<const NamedDeltas> units, std::string_view name, size_t vertices) {
  for (const NamedDeltas& u : units)
    if (u.name == name && u.deltas.size() == vertices) return &u;
  return nullptr;
}

std::vector<NamedDeltas> arkitFromUnits(std::span<const NamedDeltas> units, std::span<const glm::vec3> positions,
                                        const LandmarkFrame& frame, std::vector<std::string>& unmade) {
  std::vector<NamedDeltas> shapes;
  for (std::string_view name : facial::arkitBlendShapeNames()) {
    auto row = std::find_if(kShapes.begin(), kShapes.end(), [&](const Shape& s) { return s.name == name; });
    bool made = false;
    NamedDeltas shape{std::string(name), std::vector<glm::vec3>(positions.size(), glm::vec3(0.0f))};
    if (row != kShapes.end()) {
      for (const Term& term : row->terms) {
        if (term.unit.empty()) continue;
        const NamedDeltas* unit = findUnit(units, term.unit, positions.size());
        if (!unit) continue;
        made = true;
        for (size_t v = 0; v < positions.size(); ++v)
          shape.deltas[v] += term.gain * maskWeight(term.mask, positions[v], frame) * unit->deltas[v];
      }
    }
    if (made)
      shapes.push_back(std::move(shape));
    else
      unmade.emplace_back(name);
  }
  return shapes;
}

std::vector<ShapeShare> shapesOfUnit(std::string_view unit) {
  // jawOpen is AU26 and AU27 together; AU26's share of it is the runtime's.
  if (unit == "AU26_JawDrop") return {ShapeShare{"jawOpen", kJawDropShare}};
  // jawForward and mouthLowerDown are made from the geometry (the whole jaw
  // slid forward, the lower lip drawn down and back), not from AU29 and
  // AU16, but a face's own are its jaw thrust and lip depressor all the same.
  if (unit == "AU29_JawThrust") return {ShapeShare{"jawForward", 1.0f}};
  if (unit == "AU16_LowerLipDepressor") return {ShapeShare{"mouthLowerDownLeft", 1.0f}, ShapeShare{"mouthLowerDownRight", 1.0f}};
  std::vector<ShapeShare> shares;
  for (const Shape& shape : kShapes) {
    const bool uses = std::any_of(shape.terms.begin(), shape.terms.end(), [&](const Term& t) { return t.unit == unit; });
    if (!uses) continue;
    const bool alone = std::all_of(shape.terms.begin(), shape.terms.end(), [&](const Term& t) { return t.unit.empty() || t.unit == unit; });
    if (!alone) return {};
    shares.push_back(ShapeShare{shape.name, 1.0f});
  }
  return shares;
}

}  // namespace autorig
