#pragma once
// The Speak button's model (the window demo, the editor): a typed line is
// synthesized (spoken_line.h), played through the sound card (player.h) and
// its viseme track handed to the face, whose mouth then follows the audio
// clock each frame. Speaking again replaces the line; stop() or the line's
// end returns the mouth to the face's graph. No widgets here: the programs'
// panels and scripts drive it alike.
//
//   auto track = live.start(text, "en");          // then face.speak(*track)
//   if (auto t = live.update()) face.setSpeechTime(*t);
//   else if (face.speaking()) face.stopSpeaking();
//
// Synthesis runs on the caller's thread: 10-20 ms for a sentence, a quarter
// of a second for the longest line it takes (kMaxLiveCharacters, two minutes
// of speech; docs/audio.md).
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "audio/player.h"
#include "audio/spoken_line.h"
#include "engine/core/result.h"

namespace audio {

// A text box's worth: longer lines are refused rather than freezing the window.
inline constexpr size_t kMaxLiveCharacters = 2000;

class LiveSpeech {
 public:
  // The player opens with the first line (not before: a program that never
  // speaks never touches the sound card).
  explicit LiveSpeech(const PlayerOptions& player = {}) : playerOptions_(player) {}

  // Synthesizes `text` in `language` (an espeak-ng voice: "en", "vi", ...)
  // and starts playing it from its beginning, replacing any line playing.
  // Returns the line's viseme track for the face. Errors (the line playing
  // goes on): blank or over-long text, an unknown language.
  eng::Result<std::shared_ptr<const facial::VisemeTrack>> start(std::string_view text, std::string_view language);
  // The line's time on the audio clock, seconds from its start; none when
  // nothing is playing (before start(), after stop() or the line's end).
  std::optional<float> update();
  void stop();
  bool speaking() const { return line_.has_value(); }
  // The track of the line playing; null when none.
  const facial::VisemeTrack* track() const { return line_ ? line_->track.get() : nullptr; }
  const std::string& text() const { return text_; }
  double lineSeconds() const { return line_ ? line_->seconds() : 0.0; }
  // The line started last, for the log: "\"TEXT\" (LANGUAGE, 2.31 s)".
  std::string describe() const;
  // What the program prints once after start(): the line's warnings
  // (phonemes the track could not map) and, the first time it is known, why
  // there is no sound ("sound off: no audio output device (the face speaks
  // silently)"). Empty while all is well.
  std::vector<std::string> takeNotes();

 private:
  PlayerOptions playerOptions_;
  std::optional<Player> player_;
  std::optional<SpokenLine> line_;
  std::string text_, language_;
  std::vector<std::string> warnings_;
  bool noteTaken_ = false;
};

}  // namespace audio
