#pragma once
// The one home of the editor's hover help: every control of every panel calls
// tooltip() right after it (tests/editor/editor_tooltips_test.cpp checks the
// sources for it), saying what the control does and its shortcut if it has one.
#include <string>

namespace editor {

// Shows `text` while the last widget is hovered (disabled ones too, so a greyed
// button still says what it would do). `delaySeconds`: only after the mouse has
// rested on it that long (the canvases' own help, which would otherwise follow
// every move over them).
void tooltip(const char* text, float delaySeconds = 0.0f);
inline void tooltip(const std::string& text, float delaySeconds = 0.0f) { tooltip(text.c_str(), delaySeconds); }

// How long the mouse rests on a canvas (dope sheet, curves, pads, diagram) before its help shows.
inline constexpr float kCanvasHelpDelay = 0.8f;

}  // namespace editor
