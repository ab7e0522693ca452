#pragma once
// Apple ARKit's 52 face blend shapes (ARFaceAnchor.BlendShapeLocation) and
// the spellings models use for them: "eyeBlinkLeft" (ARKit) or "eyeBlink_L"
// (Face Cap, many DCC exports), any case, with any prefix up to a '.', ':' or
// '|' ignored ("blendShape1.eyeBlinkLeft"). Left/Right is the face's own side,
// as in FACS.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace facial {

// How a name was spelt: no side (jawOpen), "...Left"/"...Right", or "..._L"/"..._R".
enum class ArkitSpelling : uint8_t { Unsided, LeftRight, SuffixLR };

// The 52 canonical names, ARKit spelling, in Apple's documentation order.
std::span<const std::string_view> arkitBlendShapeNames();
// Index into arkitBlendShapeNames() of a model's target name, or nullopt.
// `spelling` (optional) receives how a sided name was spelt.
std::optional<uint32_t> arkitIndex(std::string_view targetName, ArkitSpelling* spelling = nullptr);

}  // namespace facial
