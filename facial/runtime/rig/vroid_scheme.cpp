// VRoid scheme: VRoid Studio's face blend shapes, "Fcl_<part>_<name>" with
// part ALL (whole face), BRW (brows), EYE, MTH (mouth), HA (teeth). Whole-face
// emotions come from Fcl_ALL_<Joy|Angry|Sorrow|Surprised|Neutral>, else from
// the BRW + EYE + MTH parts of the same name; fear and disgust, which VRoid
// does not model, are composed from parts (see kComposed); blinks come from
// Fcl_EYE_Close_L/_R (or Fcl_EYE_Close), the jaw from the vowel Fcl_MTH_A.
#include <array>
#include <optional>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

// "fcl_brw_angry" for "Face.Fcl_BRW_Angry" (prefix up to '.', ':' or '|' dropped), or nullopt.
std::optional<std::string> vroidKey(std::string_view name) {
  if (const size_t cut = name.find_last_of(".:|"); cut != std::string_view::npos) name = name.substr(cut + 1);
  const std::string key = asciiLower(name);
  for (std::string_view part : {"fcl_all_", "fcl_brw_", "fcl_eye_", "fcl_mth_", "fcl_ha_"})
    if (key.size() > part.size() && key.compare(0, part.size(), part) == 0) return key;
  return std::nullopt;
}

std::vector<uint32_t> findKey(std::span<const std::string> names, std::string_view key) {
  std::vector<uint32_t> found;
  for (uint32_t t = 0; t < names.size(); ++t)
    if (vroidKey(names[t]) == key) found.push_back(t);
  return found;
}

struct EmotionShapes {
  Emotion emotion;
  std::string_view suffix;  // VRoid's name for it: Fcl_ALL_<suffix>, Fcl_BRW_<suffix>, ...
};
constexpr std::array kEmotions = {
    EmotionShapes{Emotion::Neutral, "neutral"}, EmotionShapes{Emotion::Happy, "joy"},
    EmotionShapes{Emotion::Sad, "sorrow"},      EmotionShapes{Emotion::Anger, "angry"},
    EmotionShapes{Emotion::Surprise, "surprised"},
};

struct PartGain {
  std::string_view key;
  float gain;
};
struct Composed {
  Emotion emotion;
  std::array<PartGain, 3> parts;     // from the BRW/EYE/MTH parts
  std::array<PartGain, 2> fallback;  // whole-face shapes when the parts are missing
};
// Why these parts: fear raises the inner brows (Sorrow brows) over wide eyes
// and a dropped, stretched mouth (Surprised eyes / mouth, milder); disgust
// lowers the brows and narrows the eyes (Angry) with the upper lip drawn up
// off the teeth (VRoid's Angry mouth bares them).
constexpr std::array kComposed = {
    Composed{Emotion::Fear,
             {PartGain{"fcl_brw_sorrow", 1.0f}, PartGain{"fcl_eye_surprised", 0.8f}, PartGain{"fcl_mth_surprised", 0.45f}},
             {PartGain{"fcl_all_surprised", 0.55f}, PartGain{"fcl_all_sorrow", 0.45f}}},
    Composed{Emotion::Disgust,
             {PartGain{"fcl_brw_angry", 0.7f}, PartGain{"fcl_eye_angry", 0.6f}, PartGain{"fcl_mth_angry", 0.5f}},
             {PartGain{"fcl_all_angry", 0.5f}, PartGain{"fcl_all_sorrow", 0.3f}}},
};

}  // namespace

SchemeRecognition recogniseVRoid(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  size_t all = 0, parts = 0;
  for (const std::string& name : targetNames) {
    const std::optional<std::string> key = vroidKey(name);
    if (!key) continue;
    ++r.recognised;
    (key->compare(0, 8, "fcl_all_") == 0 ? all : parts) += 1;
  }
  r.detail = std::to_string(r.recognised) + " of " + std::to_string(targetNames.size()) + " targets are VRoid Fcl_ shapes (" +
             std::to_string(all) + " whole-face ALL, " + std::to_string(parts) + " BRW/EYE/MTH/HA parts)";
  return r;
}

void mapVRoid(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  for (const EmotionShapes& e : kEmotions) {
    std::vector<uint32_t> whole = findKey(names, "fcl_all_" + std::string(e.suffix));
    if (!whole.empty()) {
      for (uint32_t t : whole) builder.add(emotionInput(e.emotion), t, 1.0f);
      continue;
    }
    for (std::string_view part : {"fcl_brw_", "fcl_eye_", "fcl_mth_"})
      for (uint32_t t : findKey(names, std::string(part) + std::string(e.suffix))) builder.add(emotionInput(e.emotion), t, 1.0f);
  }
  for (const Composed& c : kComposed) {
    bool fromParts = false;
    for (const PartGain& p : c.parts)
      for (uint32_t t : findKey(names, p.key)) {
        builder.add(emotionInput(c.emotion), t, p.gain);
        fromParts = true;
      }
    if (fromParts) continue;
    for (const PartGain& p : c.fallback)
      for (uint32_t t : findKey(names, p.key)) builder.add(emotionInput(c.emotion), t, p.gain);
  }
  if (!findKey(names, "fcl_all_fun").empty() || !findKey(names, "fcl_mth_fun").empty())
    builder.note("Fun (VRM's relaxed) is not one of the seven emotions; its shapes stay free for other drivers");

  const uint32_t blinkL = *actionUnitIndex("AU45_Blink_L");
  const uint32_t blinkR = *actionUnitIndex("AU45_Blink_R");
  const std::vector<uint32_t> left = findKey(names, "fcl_eye_close_l");
  const std::vector<uint32_t> right = findKey(names, "fcl_eye_close_r");
  if (!left.empty() && !right.empty()) {
    for (uint32_t t : left) builder.add(blinkL, t, 1.0f);
    for (uint32_t t : right) builder.add(blinkR, t, 1.0f);
  } else {
    for (uint32_t t : findKey(names, "fcl_eye_close")) {
      builder.add(blinkL, t, 0.5f);
      builder.add(blinkR, t, 0.5f);
    }
  }
  // The open vowel is VRoid's only jaw shape: a full jaw drop opens it most of the way.
  for (uint32_t t : findKey(names, "fcl_mth_a")) {
    builder.add(*actionUnitIndex("AU26_JawDrop"), t, 0.7f);
    builder.add(*actionUnitIndex("AU25_LipsPart"), t, 0.2f);
  }
  builder.note("VRoid rigs take the emotion channels (fear and disgust composed from brow, eye and mouth parts); "
               "among the action units only AU45 (Fcl_EYE_Close) and AU25/AU26 (Fcl_MTH_A) are mapped");
}

}  // namespace facial
