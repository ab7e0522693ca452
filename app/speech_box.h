#pragma once
// The Speak box of the window demo and the editor (ImGui): a text field, a
// language field and Speak / Stop buttons, with the line's progress or the
// last problem below. It only draws and reports what was pressed; the
// program speaks through audio::LiveSpeech (audio/live_speech.h), so the
// scripts drive the same path as the buttons.
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace app {

class SpeechBox {
 public:
  enum class Action { None, Speak, Stop };
  // What the box shows under its buttons: the line playing (time of seconds) or nothing.
  struct Progress {
    bool speaking = false;
    float time = 0.0f, seconds = 0.0f;
  };
  // Draws the box at the cursor, `width` pixels wide. Speak: the button or
  // Enter in the text field (the caller reads text() and language()).
  Action draw(const Progress& progress, float width);

  std::string text() const { return text_.data(); }
  std::string language() const { return language_.data(); }
  // As typed into the fields (a script's say and say-lang); cut to the fields' size.
  void setText(std::string_view text);
  void setLanguage(std::string_view language);
  // The last problem (shown in red) or note (grey) under the box; empty: none.
  void show(std::string message, bool problem);
  // Reports a line that could not start (red, and "PROGRAM: PROBLEM" on stderr)
  // or one that did ("speech: LINE" on stdout, its notes on stderr and the last under the box).
  void reportProblem(const char* program, const std::string& problem);
  void reportStarted(const char* program, const std::string& line, const std::vector<std::string>& notes);

 private:
  std::array<char, 2001> text_{};  // audio::kMaxLiveCharacters and its terminator
  std::array<char, 24> language_{'e', 'n'};
  std::string message_;
  bool problem_ = false;
};

}  // namespace app
