#include "audio/live_speech.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace audio {

eng::Result<std::shared_ptr<const facial::VisemeTrack>> LiveSpeech::start(std::string_view text,
                                                                           std::string_view language) {
  if (std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); }))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "speech: nothing to say: the text is empty");
  if (text.size() > kMaxLiveCharacters)
    return eng::makeError(eng::ErrorKind::TooLarge, "speech: the text is " + std::to_string(text.size()) +
                                                        " bytes; at most " + std::to_string(kMaxLiveCharacters) +
                                                        " are spoken live (facial say takes longer texts)");
  auto line = speakLine(text, {.language = std::string(language)});
  if (!line) return line.error();  // "speech: unknown language 'xx' (...)", ...
  if (!player_) player_.emplace(Player::open(playerOptions_));
  if (auto played = player_->play(line->samples, line->sampleRate); !played) return played.error();
  warnings_ = std::move(line->warnings);
  text_ = std::string(text);
  language_ = std::string(language);
  line_ = std::move(*line);
  return line_->track;
}

std::optional<float> LiveSpeech::update() {
  if (!line_) return std::nullopt;
  if (player_->finished()) {
    stop();
    return std::nullopt;
  }
  return float(player_->clockSeconds());
}

void LiveSpeech::stop() {
  if (player_) player_->stop();
  line_.reset();
}

std::string LiveSpeech::describe() const {
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.2f s", lineSeconds());
  return "\"" + text_ + "\" (" + language_ + ", " + seconds + ")";
}

std::vector<std::string> LiveSpeech::takeNotes() {
  std::vector<std::string> notes = std::move(warnings_);
  warnings_.clear();
  // play() may silence a player that opened with sound (a refused rate), so the note is read after each line.
  if (!noteTaken_ && player_ && !player_->hasSound()) {
    noteTaken_ = true;
    notes.push_back(player_->note() + " (the face speaks silently)");
  }
  return notes;
}

}  // namespace audio
