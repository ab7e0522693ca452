#pragma once
// Playback through the sound card with an audio clock (PortAudio): a
// presenter's mouth follows clockSeconds(), the time of the sample being
// heard, not the frame clock, so lips and sound stay together however the
// frames are paced. Without a sound device (CI, ssh, a server) the player is
// silent: its clock runs in real time from a steady clock, and note() says
// once why sound is off.
#include <memory>
#include <span>
#include <string>

#include "engine/core/result.h"

namespace audio {

struct PlayerOptions {
  bool silent = false;  // no sound device even when one exists (tests, --mute)
};

class Player {
 public:
  // Never fails: when PortAudio or the default output cannot be opened, the
  // player is silent and note() says why.
  static Player open(const PlayerOptions& options = {});
  Player(Player&&) noexcept;
  Player& operator=(Player&&) noexcept;
  ~Player();

  bool hasSound() const;
  // Empty when sound is on; otherwise one line for the caller to print once,
  // e.g. "sound off: no audio output device (PortAudio: ...)".
  const std::string& note() const;

  // Starts `samples` (mono, -1..1, copied) from its beginning, replacing
  // whatever was playing. sampleRate 8000..192000; at most 30 minutes. A
  // device that refuses the clip (its rate) makes the player silent and
  // sets note(): check it after play() too.
  eng::Result<void> play(std::span<const float> samples, int sampleRate);
  // Seconds into the clip of the sample being heard now: 0 before play(),
  // frozen by stop(), never past the clip's end.
  double clockSeconds() const;
  bool finished() const;  // the whole clip has been heard (or stopped)
  void stop();

 private:
  struct Impl;
  explicit Player(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace audio
