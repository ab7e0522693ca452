#include "facial/runtime/rig/emotions.h"

#include <string>

#include <array>

namespace facial {
namespace {

constexpr std::array<std::string_view, kEmotionCount> kEmotionNames = {
    "neutral", "happy", "sad", "surprise", "fear", "anger", "disgust",
};

}  // namespace

std::span<const std::string_view> emotionNames() { return kEmotionNames; }

std::string_view emotionName(Emotion emotion) { return kEmotionNames[static_cast<size_t>(emotion)]; }

std::string emotionNameList() {
  std::string list;
  for (std::string_view name : kEmotionNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

std::optional<uint32_t> emotionIndex(std::string_view name) {
  for (uint32_t i = 0; i < kEmotionNames.size(); ++i)
    if (kEmotionNames[i] == name) return i;
  return std::nullopt;
}

}  // namespace facial
