#pragma once
// Timings from elsewhere, read into what VisemeTrackBuilder takes. Each
// reader gets the text and the name of its source (a file name) and fails
// with one line: "<source>: <JSON pointer or line N>: <problem>" (Malformed;
// TooLarge over maxCues or past kMaxSpeechSeconds; Unsupported for a newer
// version of the project's own formats). Times must be finite, start at or
// after 0, sorted and not overlapping; gaps are silence.
//
//  - phonemesFromJson: the project's timed phonemes,
//      {"version": 1, "phonemes": [{"ipa": "h", "start": 0.0, "end": 0.06}, ...]}
//  - visemesFromJson: the project's timed visemes,
//      {"version": 1, "visemes": [{"viseme": "PP", "start": 0.1, "end": 0.18}, ...]}
//  - rhubarbFromJson / rhubarbFromTsv: Rhubarb Lip Sync's output ("mouthCues"
//    with shapes A-H and X; or "0.00<TAB>X" lines, the last line marking the end)
//  - azureVisemesFromJson: Azure Speech viseme events, an array of
//      {"visemeId": 0..21, "audioOffset": <100-ns ticks>} or {"visemeId": .., "offsetMs": ..};
//    each event lasts until the next, the last one kAzureLastEventSeconds
//  - wordVisemesFromJson: word timestamps, {"words": [{"word": "Good", "start": 0.0, "end": 0.3}, ...]}
//    (OpenAI/Whisper-style; other members such as "probability" are ignored),
//    each word spread over its interval by visemesForWord.
// The project's formats refuse unknown members; the third-party ones ignore
// them (their writers add fields between versions).
#include <optional>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/speech/viseme_track.h"

namespace facial {

inline constexpr int kSpeechTimingsVersion = 1;
inline constexpr float kAzureLastEventSeconds = 0.1f;

eng::Result<std::vector<TimedPhoneme>> phonemesFromJson(std::string_view text, std::string_view source,
                                                        size_t maxCues = kMaxSpeechCues);
eng::Result<std::vector<TimedViseme>> visemesFromJson(std::string_view text, std::string_view source,
                                                      size_t maxCues = kMaxSpeechCues);
eng::Result<std::vector<TimedViseme>> rhubarbFromJson(std::string_view text, std::string_view source,
                                                      size_t maxCues = kMaxSpeechCues);
eng::Result<std::vector<TimedViseme>> rhubarbFromTsv(std::string_view text, std::string_view source,
                                                     size_t maxCues = kMaxSpeechCues);
eng::Result<std::vector<TimedViseme>> azureVisemesFromJson(std::string_view text, std::string_view source,
                                                           size_t maxCues = kMaxSpeechCues);
eng::Result<std::vector<TimedViseme>> wordVisemesFromJson(std::string_view text, std::string_view source,
                                                          size_t maxCues = kMaxSpeechCues);

// Rhubarb's mouth shapes (README "Mouth shapes"): A closed (P B M) -> PP,
// B clenched teeth (most consonants, EE) -> SS, C open (EH, AE) -> E,
// D wide open (AA) -> aa, E slightly rounded (AO, ER) -> O, F puckered
// (UW, OW, W) -> U, G upper teeth on lower lip (F, V) -> FF, H tongue up (L)
// -> nn (Oculus puts l there), X rest -> sil.
std::optional<Viseme> visemeForRhubarbShape(char shape);
// Azure's 22 viseme ids (the SAPI/Disney set: 0 silence, 1 ae ax ah, ...,
// 21 p b m) to the nearest Oculus viseme; nullopt outside 0..21.
std::optional<Viseme> visemeForAzureId(int id);
// A written word's visemes by a letter rule (a few digraphs, then one
// viseme per letter, repeats merged, h silent); accented Latin letters count
// as their base letter. Empty when the word has no letters.
std::vector<Viseme> visemesForWord(std::string_view word);

}  // namespace facial
