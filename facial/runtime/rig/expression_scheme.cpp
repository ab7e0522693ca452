// Expressions scheme: rigs whose controls are whole expressions (VRM 1.0 /
// 0.x presets, or targets named after emotions such as RobotExpressive's
// "Angry"/"Surprised"/"Sad"). The emotion channels drive them; AU45 drives blink.
#include <array>
#include <utility>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

struct Aliases {
  Emotion emotion;
  std::array<std::string_view, 4> names;  // lower case; VRM 1.0 name first, then VRM 0.x
};

constexpr std::array kEmotionAliases = {
    Aliases{Emotion::Neutral, {"neutral"}},
    Aliases{Emotion::Happy, {"happy", "joy"}},
    Aliases{Emotion::Sad, {"sad", "sorrow"}},
    Aliases{Emotion::Surprise, {"surprised", "surprise"}},
    Aliases{Emotion::Fear, {"fear", "fearful", "afraid", "scared"}},
    Aliases{Emotion::Anger, {"angry", "anger"}},
    Aliases{Emotion::Disgust, {"disgust", "disgusted"}},
};
// VRM 1.0 relaxed / 0.x fun: content, eyes half closed. Not one of the seven.
constexpr std::array<std::string_view, 2> kRelaxed = {"relaxed", "fun"};
constexpr std::array<std::string_view, 1> kBlink = {"blink"};
constexpr std::array<std::string_view, 2> kBlinkLeft = {"blinkleft", "blink_l"};
constexpr std::array<std::string_view, 2> kBlinkRight = {"blinkright", "blink_r"};

std::string key(std::string_view name) {
  if (const size_t cut = name.find_last_of(".:|"); cut != std::string_view::npos) name = name.substr(cut + 1);
  return asciiLower(name);
}

// Every target named by the first alias that names any (a face and its
// eyelashes may both carry "blink").
template <size_t N>
std::vector<uint32_t> findAll(std::span<const std::string> names, const std::array<std::string_view, N>& aliases) {
  std::vector<uint32_t> found;
  for (std::string_view alias : aliases) {
    if (alias.empty()) continue;
    for (uint32_t t = 0; t < names.size(); ++t)
      if (key(names[t]) == alias) found.push_back(t);
    if (!found.empty()) break;
  }
  return found;
}

std::vector<uint32_t> targetsOf(std::span<const std::string> names, Emotion emotion) {
  for (const Aliases& a : kEmotionAliases)
    if (a.emotion == emotion) return findAll(names, a.names);
  return {};
}

// VRM 0.x has no surprised preset (1.0 has): such an avatar shows surprise
// by the round open mouth of its vowel O ('o', VRM 1.0 'oh'), the one part
// of surprise its presets have.
constexpr std::array<std::string_view, 3> kRoundOpenMouth = {"oh", "o", "viseme_o"};
constexpr float kSurpriseMouth = 0.8f;

// The targets that show `emotion`, with their gains: its own at 1, else,
// for surprise, the round open mouth.
std::vector<std::pair<uint32_t, float>> shownBy(std::span<const std::string> names, Emotion emotion) {
  std::vector<std::pair<uint32_t, float>> shown;
  for (uint32_t t : targetsOf(names, emotion)) shown.emplace_back(t, 1.0f);
  if (shown.empty() && emotion == Emotion::Surprise)
    for (uint32_t t : findAll(names, kRoundOpenMouth)) shown.emplace_back(t, kSurpriseMouth);
  return shown;
}

bool isExpressionName(const std::string& name) {
  const std::string k = key(name);
  auto in = [&](const auto& list) {
    for (std::string_view alias : list)
      if (!alias.empty() && k == alias) return true;
    return false;
  };
  for (const Aliases& a : kEmotionAliases)
    if (in(a.names)) return true;
  return in(kRelaxed) || in(kBlink) || in(kBlinkLeft) || in(kBlinkRight);
}

// An emotion the rig lacks, approximated by neighbours it has (fear reads as
// surprise with distress, disgust as a milder anger with sadness).
struct Fallback {
  Emotion missing;
  Emotion a;
  float gainA;
  Emotion b;
  float gainB;
};
constexpr std::array kFallbacks = {
    Fallback{Emotion::Fear, Emotion::Surprise, 0.55f, Emotion::Sad, 0.45f},
    Fallback{Emotion::Disgust, Emotion::Anger, 0.5f, Emotion::Sad, 0.3f},
};

}  // namespace

SchemeRecognition recogniseExpressions(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  for (const std::string& name : targetNames) r.recognised += isExpressionName(name) ? 1 : 0;
  r.detail = std::to_string(r.recognised) + " of " + std::to_string(targetNames.size()) +
             " targets are emotion / blink expressions";
  return r;
}

void mapExpressions(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  for (const Aliases& a : kEmotionAliases)
    for (uint32_t t : findAll(names, a.names)) builder.add(emotionInput(a.emotion), t, 1.0f);
  if (const std::vector<uint32_t> relaxed = findAll(names, kRelaxed); !relaxed.empty()) {
    if (targetsOf(names, Emotion::Happy).empty()) {
      for (uint32_t t : relaxed) builder.add(emotionInput(Emotion::Happy), t, 1.0f);
      builder.note("happy: the rig has no happy / joy expression; '" + names[relaxed[0]] + "' stands in for it");
    } else {
      builder.note("'" + names[relaxed[0]] + "' is not one of the seven emotions; it stays free for other drivers");
    }
  }

  if (targetsOf(names, Emotion::Surprise).empty()) {
    const std::vector<std::pair<uint32_t, float>> mouth = shownBy(names, Emotion::Surprise);
    for (auto [t, gain] : mouth) builder.add(emotionInput(Emotion::Surprise), t, gain);
    if (!mouth.empty())
      builder.note("surprise: the rig has no such expression; approximated as '" + names[mouth[0].first] + "' " +
                   formatNumber(kSurpriseMouth) + " (the round open mouth)");
  }
  for (const Fallback& f : kFallbacks) {
    if (!targetsOf(names, f.missing).empty()) continue;
    std::string how;
    for (auto [neighbour, gain] : {std::pair{f.a, f.gainA}, std::pair{f.b, f.gainB}}) {
      const std::vector<std::pair<uint32_t, float>> shown = shownBy(names, neighbour);
      for (auto [t, own] : shown) builder.add(emotionInput(f.missing), t, gain * own);
      if (!shown.empty())
        how += std::string(how.empty() ? "" : " + ") + "'" + names[shown[0].first] + "' " + formatNumber(gain * shown[0].second);
    }
    if (!how.empty())
      builder.note(std::string(emotionName(f.missing)) + ": the rig has no such expression; approximated as " + how);
  }

  const uint32_t blinkL = *actionUnitIndex("AU45_Blink_L");
  const uint32_t blinkR = *actionUnitIndex("AU45_Blink_R");
  const std::vector<uint32_t> left = findAll(names, kBlinkLeft);
  const std::vector<uint32_t> right = findAll(names, kBlinkRight);
  if (!left.empty() && !right.empty()) {
    for (uint32_t t : left) builder.add(blinkL, t, 1.0f);
    for (uint32_t t : right) builder.add(blinkR, t, 1.0f);
  } else {
    for (uint32_t t : findAll(names, kBlink)) {
      builder.add(blinkL, t, 0.5f);
      builder.add(blinkR, t, 0.5f);
    }
  }
  builder.note("expression rigs take the emotion channels; among the action units only AU45 (blink) is mapped, "
               "the expressions carry their own brows and mouth");
}

}  // namespace facial
