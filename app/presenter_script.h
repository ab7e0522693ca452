#pragma once
// `facial say --script FILE`: a presenter's bulletin in one file. The model
// and its reader only (no audio, no rendering: cli/say_speech.cpp speaks it).
//
// Text form, for a newsroom: lines of text spoken in order; a tag in square
// brackets switches the emotion from that point on, in the middle of a line
// too, and holds until the next tag; '#' starts a comment line.
//
//   # Evening bulletin
//   [happy] Good evening, and welcome.
//   The sun is out all week, [sad 0.6] but the final was lost.
//   [pause 1.5]
//   [neutral] That is all for tonight.
//
//   [emotion]      neutral, happy, sad, anger, fear, surprise, disgust, at the default intensity
//   [emotion X]    ... at intensity X in [0, 1]
//   [pause S]      S seconds of silence, 0..60
//   a line break   a short pause (kLinePauseSeconds); a blank line a paragraph pause
//
// JSON form (the first character is '{'), for tools that write bulletins:
//   {"version": 1, "lines": [{"text": "Good evening.", "emotion": "happy", "intensity": 0.8, "pause": 1.0}, ...]}
// "emotion" and "intensity" switch before the line (absent: unchanged), "pause"
// is the silence after it (absent: kLinePauseSeconds); the text may hold tags.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace app {

inline constexpr size_t kMaxPresenterScriptBytes = size_t{1} << 20;
inline constexpr float kMaxScriptPauseSeconds = 60.0f;
inline constexpr float kLinePauseSeconds = 0.3f;
inline constexpr float kParagraphPauseSeconds = 1.0f;

struct ScriptSegment {
  enum class Kind { Speech, Pause };
  Kind kind = Kind::Speech;
  std::string text;       // Speech: what is said (no tags, trimmed, never empty)
  std::string emotion;    // Speech: one of facial::emotionNames()
  float intensity = 1.0f;  // Speech: 0..1
  float seconds = 0.0f;   // Pause: silence
  int line = 0;           // 1-based line of the text form, the line's index + 1 in the JSON form
};

struct PresenterScript {
  std::vector<ScriptSegment> segments;  // at least one Speech; no Pause first or last, no two in a row
};

// What the script starts with, and the intensity of a tag that gives none.
struct ScriptDefaults {
  std::string emotion = "neutral";
  float intensity = 1.0f;
};

// Errors are one line, "SOURCE:LINE: problem" (text form) or "SOURCE:
// /lines/N/key: problem" (JSON form): an unknown emotion or tag, a bad pause
// or intensity, an unclosed '[' or a stray ']', a script that says nothing.
eng::Result<PresenterScript> parsePresenterScript(std::string_view text, std::string_view source,
                                                  const ScriptDefaults& defaults = {});
// The file, refused past kMaxPresenterScriptBytes before it is read.
eng::Result<PresenterScript> loadPresenterScript(const std::filesystem::path& path,
                                                 const ScriptDefaults& defaults = {});

}  // namespace app
