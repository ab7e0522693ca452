#pragma once
// The emotion channel vocabulary: the six basic emotions (Ekman & Friesen)
// plus neutral. Action units drive FACS-capable rigs; emotion channels drive
// rigs whose controls are whole expressions (VRM `happy`/`joy`, a robot's
// `Angry` target). A pose over emotions is a float per entry of emotions(),
// in this order.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace facial {

enum class Emotion : uint8_t { Neutral, Happy, Sad, Surprise, Fear, Anger, Disgust };
inline constexpr size_t kEmotionCount = 7;

// Channel names ("neutral", "happy", "sad", "surprise", "fear", "anger", "disgust").
std::span<const std::string_view> emotionNames();
std::string_view emotionName(Emotion emotion);
// Channel index of a name, or nullopt. Exact, lower-case match.
std::optional<uint32_t> emotionIndex(std::string_view name);
// "neutral, happy, sad, ..." for messages that list the accepted names.
std::string emotionNameList();

}  // namespace facial
