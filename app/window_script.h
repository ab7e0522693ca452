#pragma once
// `facial demo --script FILE`: timed actions for the window demo, so a
// presentation, a recording or a test can drive the same code paths as the
// keys, the panel and the mouse. One action per line, "SECONDS ACTION ARGS",
// seconds of animation since the window opened (WindowTick::animationTime:
// wall time, except that a frame slower than 0.1 s counts as 0.1 s, so an
// action lands at the same point of a transition however loaded the
// machine), in ascending order; '#' starts a comment:
//
//   1.0  trigger happy      the state machine's trigger, as key 2 or the panel button
//   1.5  intensity 0.4      the slider: neutral -> the chosen expression at 0.4
//   2.0  pad 0.7 -0.2       the control-map pad's cursor (x right, y up, [-1, 1])
//   2.5  graph              give control back to the graph (the panel's button)
//   3.0  orbit 30 -10       turn the camera by yaw/pitch degrees, as a mouse drag
//   3.5  screenshot         as F12
//   4.0  resize 900 600     the window's size in screen coordinates
//   4.5  iconify            minimise / restore through the window manager
//   5.0  restore
//   6.0  say-lang vi        the Speak box's language (an espeak-ng voice; "en" until set)
//   6.5  say Xin chào!      the Speak box's text (the rest of the line) and its Speak button
//   9.0  say-stop           the Stop button
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace app {

struct ScriptAction {
  enum class Kind { Trigger, Intensity, Pad, Graph, Orbit, Frame, Screenshot, Resize, Iconify, Restore, Say, SayLanguage, SayStop };
  float time = 0.0f;
  Kind kind = Kind::Screenshot;
  std::string name;   // Trigger: the trigger parameter; Say: the text; SayLanguage: the language
  float a = 0, b = 0;  // Intensity: a; Pad, Orbit: a, b; Resize: a x b
};

// The timed lines of any such script, before their actions are read: blank
// lines and '#' comments dropped, the leading time checked (a number >= 0, not
// before the previous line's). Other programs with their own actions (the
// editor's --script) build on this and report "SOURCE:LINE: problem" alike.
struct TimedScriptLine {
  float time = 0.0f;
  int line = 0;                     // 1-based, for messages
  std::vector<std::string> words;   // the action and its arguments (at least the action)
};
eng::Result<std::vector<TimedScriptLine>> splitTimedScript(std::string_view text, std::string_view source);
// The script's whole text; the error names the file.
eng::Result<std::string> readScriptFile(const std::filesystem::path& path);
// A finite number spelt entirely by `word`.
bool parseScriptNumber(const std::string& word, float& value);

// Errors read "SOURCE:LINE: problem" (unknown action, missing or extra
// arguments, non-finite numbers, values out of range, times going backwards).
eng::Result<std::vector<ScriptAction>> parseWindowScript(std::string_view text, std::string_view source);
eng::Result<std::vector<ScriptAction>> loadWindowScript(const std::filesystem::path& path);

}  // namespace app
