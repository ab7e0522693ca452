#include "facial/runtime/rig/arkit_names.h"

#include <array>
#include <string>

#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

constexpr std::array<std::string_view, 52> kArkitNames = {
    "eyeBlinkLeft",      "eyeLookDownLeft",   "eyeLookInLeft",    "eyeLookOutLeft",   "eyeLookUpLeft",
    "eyeSquintLeft",     "eyeWideLeft",       "eyeBlinkRight",    "eyeLookDownRight", "eyeLookInRight",
    "eyeLookOutRight",   "eyeLookUpRight",    "eyeSquintRight",   "eyeWideRight",     "jawForward",
    "jawLeft",           "jawRight",          "jawOpen",          "mouthClose",       "mouthFunnel",
    "mouthPucker",       "mouthLeft",         "mouthRight",       "mouthSmileLeft",   "mouthSmileRight",
    "mouthFrownLeft",    "mouthFrownRight",   "mouthDimpleLeft",  "mouthDimpleRight", "mouthStretchLeft",
    "mouthStretchRight", "mouthRollLower",    "mouthRollUpper",   "mouthShrugLower",  "mouthShrugUpper",
    "mouthPressLeft",    "mouthPressRight",   "mouthLowerDownLeft", "mouthLowerDownRight", "mouthUpperUpLeft",
    "mouthUpperUpRight", "browDownLeft",      "browDownRight",    "browInnerUp",      "browOuterUpLeft",
    "browOuterUpRight",  "cheekPuff",         "cheekSquintLeft",  "cheekSquintRight", "noseSneerLeft",
    "noseSneerRight",    "tongueOut",
};

bool endsWith(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

}  // namespace

std::span<const std::string_view> arkitBlendShapeNames() { return kArkitNames; }

std::optional<uint32_t> arkitIndex(std::string_view targetName, ArkitSpelling* spelling) {
  if (const size_t cut = targetName.find_last_of(".:|"); cut != std::string_view::npos)
    targetName = targetName.substr(cut + 1);
  std::string key = asciiLower(targetName);
  ArkitSpelling spelt = ArkitSpelling::Unsided;
  // "jawLeft"/"mouthLeft" are names of their own, so only "_l"/"_r" are rewritten.
  if (endsWith(key, "_l")) {
    key.replace(key.size() - 2, 2, "left");
    spelt = ArkitSpelling::SuffixLR;
  } else if (endsWith(key, "_r")) {
    key.replace(key.size() - 2, 2, "right");
    spelt = ArkitSpelling::SuffixLR;
  } else if (endsWith(key, "left") || endsWith(key, "right")) {
    spelt = ArkitSpelling::LeftRight;
  }
  for (uint32_t i = 0; i < kArkitNames.size(); ++i) {
    if (key == asciiLower(kArkitNames[i])) {
      if (spelling) *spelling = spelt;
      return i;
    }
  }
  return std::nullopt;
}

}  // namespace facial
