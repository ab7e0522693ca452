#include "facial/runtime/speech/speech_timings.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include "facial/runtime/json/json_node.h"
#include "facial/runtime/speech/utf8_text.h"

namespace facial {
namespace {

eng::Error tooMany(size_t count, size_t maxCues) {
  return eng::makeError(eng::ErrorKind::TooLarge,
                        std::to_string(count) + " cues, over the limit of " + std::to_string(maxCues));
}

// The cue array at `key`: present, an array, not empty, within maxCues.
eng::Result<JsonNode> cueArray(const JsonNode& root, std::string_view key, size_t maxCues) {
  const JsonNode array = ENG_TRY_VALUE(root.at(key));
  const size_t count = ENG_TRY_VALUE(array.size());
  if (count == 0) return array.error("no cues");
  if (count > maxCues) return array.error(tooMany(count, maxCues));
  return array;
}

// Reads every element with readCue, then checks its times against the previous cue's.
template <class Cue, class ReadCue>
eng::Result<std::vector<Cue>> readCues(const JsonNode& array, ReadCue readCue) {
  const size_t count = ENG_TRY_VALUE(array.size());
  std::vector<Cue> cues;
  cues.reserve(count);
  CueOrderCheck order;
  for (size_t i = 0; i < count; ++i) {
    const JsonNode item = array.element(i);
    Cue cue = ENG_TRY_VALUE(readCue(item));
    if (auto times = order.accept(cue.start, cue.end); !times) return item.error(times.error());
    cues.push_back(std::move(cue));
  }
  return cues;
}

// Parses `text` and runs `read` on its root; any error gets "<source>: " in front.
template <class T, class Read>
eng::Result<T> readDocument(std::string_view text, std::string_view source, Read read) {
  const Json document = ENG_TRY_VALUE(parseJsonText(text, source));
  eng::Result<T> result = read(JsonNode(document, ""));
  if (!result) return result.error().prefixed(std::string(source) + ": ");
  return result;
}

eng::Result<TimedViseme> readNamedViseme(const JsonNode& item) {
  ENG_TRY(item.allowOnly({"viseme", "start", "end"}));
  const JsonNode name = ENG_TRY_VALUE(item.at("viseme"));
  const std::optional<Viseme> viseme = visemeFromName(ENG_TRY_VALUE(name.string()));
  if (!viseme) return name.error("unknown viseme (expected " + visemeNameList() + ")");
  return TimedViseme{*viseme, ENG_TRY_VALUE(item.numberAt("start")), ENG_TRY_VALUE(item.numberAt("end"))};
}

eng::Result<TimedViseme> readRhubarbCue(const JsonNode& item) {
  const JsonNode value = ENG_TRY_VALUE(item.at("value"));
  const std::string shape = ENG_TRY_VALUE(value.string());
  const std::optional<Viseme> viseme = shape.size() == 1 ? visemeForRhubarbShape(shape[0]) : std::nullopt;
  if (!viseme)
    return value.error("unknown mouth shape " + quotedForMessage(shape) + " (expected A, B, C, D, E, F, G, H or X)");
  return TimedViseme{*viseme, ENG_TRY_VALUE(item.numberAt("start")), ENG_TRY_VALUE(item.numberAt("end"))};
}

}  // namespace

eng::Result<std::vector<TimedPhoneme>> phonemesFromJson(std::string_view text, std::string_view source,
                                                        size_t maxCues) {
  return readDocument<std::vector<TimedPhoneme>>(
      text, source, [&](const JsonNode& root) -> eng::Result<std::vector<TimedPhoneme>> {
        ENG_TRY(requireVersion(root, kSpeechTimingsVersion));
        ENG_TRY(root.allowOnly({"version", "phonemes"}));
        return readCues<TimedPhoneme>(
            ENG_TRY_VALUE(cueArray(root, "phonemes", maxCues)), [](const JsonNode& item) -> eng::Result<TimedPhoneme> {
              ENG_TRY(item.allowOnly({"ipa", "start", "end"}));
              const float start = ENG_TRY_VALUE(item.numberAt("start")), end = ENG_TRY_VALUE(item.numberAt("end"));
              return TimedPhoneme{ENG_TRY_VALUE(item.stringAt("ipa")), start, end};  // the string last (result.h)
            });
      });
}

eng::Result<std::vector<TimedViseme>> visemesFromJson(std::string_view text, std::string_view source, size_t maxCues) {
  return readDocument<std::vector<TimedViseme>>(
      text, source, [&](const JsonNode& root) -> eng::Result<std::vector<TimedViseme>> {
        ENG_TRY(requireVersion(root, kSpeechTimingsVersion));
        ENG_TRY(root.allowOnly({"version", "visemes"}));
        return readCues<TimedViseme>(ENG_TRY_VALUE(cueArray(root, "visemes", maxCues)), readNamedViseme);
      });
}

eng::Result<std::vector<TimedViseme>> rhubarbFromJson(std::string_view text, std::string_view source, size_t maxCues) {
  return readDocument<std::vector<TimedViseme>>(
      text, source, [&](const JsonNode& root) -> eng::Result<std::vector<TimedViseme>> {
        return readCues<TimedViseme>(ENG_TRY_VALUE(cueArray(root, "mouthCues", maxCues)), readRhubarbCue);
      });
}

namespace {

struct TsvEntry {
  float time;
  Viseme viseme;
  size_t line;
};

eng::Error lineError(size_t line, std::string_view problem, eng::ErrorKind kind = eng::ErrorKind::Malformed) {
  return eng::makeError(kind, "line " + std::to_string(line) + ": " + std::string(problem));
}

// "0.00<TAB>X": a time and a shape; blank lines are skipped (nullopt).
eng::Result<std::optional<TsvEntry>> readTsvLine(std::string_view line, size_t number) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  if (line.empty()) return std::optional<TsvEntry>();
  const size_t tab = line.find_first_of("\t ");
  if (tab == std::string_view::npos) return lineError(number, "expected a time and a mouth shape separated by a tab");
  float time = 0;
  const std::string_view field = line.substr(0, tab);
  const auto parsed = std::from_chars(field.data(), field.data() + field.size(), time);
  if (parsed.ec != std::errc() || parsed.ptr != field.data() + field.size())
    return lineError(number, quotedForMessage(field) + " is not a time in seconds");
  if (!std::isfinite(time)) return lineError(number, "time is not a finite number");
  std::string_view shape = line.substr(tab + 1);
  while (!shape.empty() && (shape.front() == '\t' || shape.front() == ' ')) shape.remove_prefix(1);
  const std::optional<Viseme> viseme = shape.size() == 1 ? visemeForRhubarbShape(shape[0]) : std::nullopt;
  if (!viseme)
    return lineError(number,
                     "unknown mouth shape " + quotedForMessage(shape) + " (expected A, B, C, D, E, F, G, H or X)");
  return std::optional<TsvEntry>(TsvEntry{time, *viseme, number});
}

eng::Result<std::vector<TimedViseme>> readTsv(std::string_view text, size_t maxCues) {
  std::vector<TsvEntry> entries;
  size_t number = 0;
  for (size_t pos = 0; pos <= text.size();) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    ++number;
    const std::optional<TsvEntry> entry = ENG_TRY_VALUE(readTsvLine(text.substr(pos, end - pos), number));
    if (entry) entries.push_back(*entry);
    // Each line but the last starts a cue: refuse as soon as the count is known to be over.
    if (entries.size() > maxCues + 1)
      return lineError(number, tooMany(entries.size() - 1, maxCues).message, eng::ErrorKind::TooLarge);
    pos = end + 1;
  }
  if (entries.size() < 2)
    return eng::makeError(
        eng::ErrorKind::Malformed,
        "needs at least two lines: each starts a mouth shape, the last marks the end of the recording");
  std::vector<TimedViseme> cues;
  cues.reserve(entries.size() - 1);
  CueOrderCheck order;
  for (size_t i = 0; i + 1 < entries.size(); ++i) {
    const float start = entries[i].time, end = entries[i + 1].time;
    if (auto times = order.accept(start, end); !times)
      return lineError(entries[i].line, times.error().message, times.error().kind);
    cues.push_back({entries[i].viseme, start, end});
  }
  return cues;
}

}  // namespace

eng::Result<std::vector<TimedViseme>> rhubarbFromTsv(std::string_view text, std::string_view source, size_t maxCues) {
  auto cues = readTsv(text, maxCues);
  if (!cues) return cues.error().prefixed(std::string(source) + ": ");
  return cues;
}

namespace {

struct AzureEvent {
  Viseme viseme;
  float offset;  // seconds
};

eng::Result<AzureEvent> readAzureEvent(const JsonNode& item) {
  const JsonNode idNode = ENG_TRY_VALUE(item.at("visemeId"));
  const float id = ENG_TRY_VALUE(idNode.number());
  const std::optional<Viseme> viseme = id == std::floor(id) ? visemeForAzureId(static_cast<int>(id)) : std::nullopt;
  if (!viseme) return idNode.error("viseme id " + formatNumber(id) + " is not one of Azure's 0..21");
  const std::optional<JsonNode> ticks = item.find("audioOffset"), ms = item.find("offsetMs");
  if (ticks.has_value() == ms.has_value())
    return item.error("expected one of \"audioOffset\" (100-ns ticks) or \"offsetMs\" (milliseconds)");
  const float offset = ticks ? ENG_TRY_VALUE(ticks->number()) * 1e-7f : ENG_TRY_VALUE(ms->number()) * 1e-3f;
  return AzureEvent{*viseme, offset};
}

eng::Result<std::vector<TimedViseme>> readAzure(const JsonNode& root, size_t maxCues) {
  const size_t count = ENG_TRY_VALUE(root.size());
  if (count == 0) return root.error("no viseme events");
  if (count > maxCues) return root.error(tooMany(count, maxCues));
  std::vector<AzureEvent> events;
  events.reserve(count);
  for (size_t i = 0; i < count; ++i) events.push_back(ENG_TRY_VALUE(readAzureEvent(root.element(i))));
  std::vector<TimedViseme> cues;
  cues.reserve(count);
  CueOrderCheck order;
  for (size_t i = 0; i < count; ++i) {
    // An event lasts until the next one starts.
    const float start = events[i].offset;
    const float end = i + 1 < count ? events[i + 1].offset : start + kAzureLastEventSeconds;
    if (auto times = order.accept(start, end); !times) return root.element(i).error(times.error());
    cues.push_back({events[i].viseme, start, end});
  }
  return cues;
}

struct TimedWord {
  std::string word;
  float start = 0;
  float end = 0;
};

// A word's visemes share its interval evenly; a viseme that continues the previous cue extends it.
void spreadWord(const TimedWord& word, std::vector<TimedViseme>& cues) {
  const std::vector<Viseme> visemes = visemesForWord(word.word);
  const float step = (word.end - word.start) / static_cast<float>(std::max<size_t>(visemes.size(), 1));
  for (size_t i = 0; i < visemes.size(); ++i) {
    // Both ends from the same expression, so that one cue ends exactly where the next starts.
    const float start = word.start + step * static_cast<float>(i);
    const float end = i + 1 == visemes.size() ? word.end : word.start + step * static_cast<float>(i + 1);
    if (!cues.empty() && cues.back().viseme == visemes[i] && cues.back().end == start)
      cues.back().end = end;
    else
      cues.push_back({visemes[i], start, end});
  }
}

}  // namespace

eng::Result<std::vector<TimedViseme>> azureVisemesFromJson(std::string_view text, std::string_view source,
                                                           size_t maxCues) {
  return readDocument<std::vector<TimedViseme>>(text, source,
                                                [&](const JsonNode& root) { return readAzure(root, maxCues); });
}

eng::Result<std::vector<TimedViseme>> wordVisemesFromJson(std::string_view text, std::string_view source,
                                                          size_t maxCues) {
  return readDocument<std::vector<TimedViseme>>(
      text, source, [&](const JsonNode& root) -> eng::Result<std::vector<TimedViseme>> {
        const std::vector<TimedWord> words = ENG_TRY_VALUE(readCues<TimedWord>(
            ENG_TRY_VALUE(cueArray(root, "words", maxCues)), [](const JsonNode& item) -> eng::Result<TimedWord> {
              const float start = ENG_TRY_VALUE(item.numberAt("start")), end = ENG_TRY_VALUE(item.numberAt("end"));
              return TimedWord{ENG_TRY_VALUE(item.stringAt("word")), start, end};  // the string last (result.h)
            }));
        std::vector<TimedViseme> cues;
        for (const TimedWord& word : words) spreadWord(word, cues);
        if (cues.empty()) return root.error("no word has a letter to speak");
        return cues;
      });
}

std::optional<Viseme> visemeForRhubarbShape(char shape) {
  using V = Viseme;
  constexpr std::pair<char, Viseme> kShapes[] = {{'A', V::PP}, {'B', V::SS}, {'C', V::E},  {'D', V::aa}, {'E', V::O},
                                                 {'F', V::U},  {'G', V::FF}, {'H', V::nn}, {'X', V::sil}};
  for (const auto& [name, viseme] : kShapes)
    if (name == shape) return viseme;
  return std::nullopt;
}

std::optional<Viseme> visemeForAzureId(int id) {
  using V = Viseme;
  // 0 silence; 1 ae ax ah; 2 aa; 3 ao; 4 ey eh uh; 5 er; 6 y iy ih ix; 7 w uw; 8 ow; 9 aw; 10 oy; 11 ay;
  // 12 h (the open neutral mouth of the vowel it precedes); 13 r; 14 l; 15 s z; 16 sh ch jh zh;
  // 17 th dh; 18 f v; 19 d t n; 20 k g ng; 21 p b m.
  constexpr Viseme kAzure[] = {V::sil, V::aa, V::aa, V::O,  V::E,  V::RR, V::I,  V::U,  V::O,  V::aa, V::O,
                               V::aa,  V::E,  V::RR, V::nn, V::SS, V::CH, V::TH, V::FF, V::DD, V::kk, V::PP};
  if (id < 0 || id >= static_cast<int>(std::size(kAzure))) return std::nullopt;
  return kAzure[id];
}

namespace {

// Letters to visemes, English- and French-leaning and read by base letter
// (so Vietnamese "đ" is d, "ư" is u): good enough when only words are timed.
constexpr std::pair<std::string_view, Viseme> kDigraphs[] = {{"th", Viseme::TH}, {"sh", Viseme::CH}, {"ch", Viseme::CH},
                                                             {"ph", Viseme::FF}, {"ng", Viseme::nn}, {"qu", Viseme::kk},
                                                             {"oo", Viseme::U},  {"ou", Viseme::U},  {"ee", Viseme::I}};
// a..z; sil marks a silent letter (h).
constexpr Viseme kLetters[26] = {Viseme::aa,  Viseme::PP, Viseme::kk, Viseme::DD, Viseme::E,  Viseme::FF, Viseme::kk,
                                 Viseme::sil, Viseme::I,  Viseme::CH, Viseme::kk, Viseme::nn, Viseme::PP, Viseme::nn,
                                 Viseme::O,   Viseme::PP, Viseme::kk, Viseme::RR, Viseme::SS, Viseme::DD, Viseme::U,
                                 Viseme::FF,  Viseme::U,  Viseme::kk, Viseme::I,  Viseme::SS};

}  // namespace

std::vector<Viseme> visemesForWord(std::string_view word) {
  std::string letters;
  for (size_t pos = 0; pos < word.size();)
    if (const char base = latinBaseLetter(nextCodepoint(word, pos))) letters += base;
  std::vector<Viseme> out;
  const auto add = [&](Viseme v) {
    if (v != Viseme::sil && (out.empty() || out.back() != v)) out.push_back(v);
  };
  for (size_t i = 0; i < letters.size();) {
    bool digraph = false;
    for (const auto& [pair, viseme] : kDigraphs)
      if (letters.compare(i, 2, pair) == 0) {
        add(viseme);
        digraph = true;
        break;
      }
    if (!digraph) add(kLetters[letters[i] - 'a']);
    i += digraph ? 2 : 1;
  }
  return out;
}

}  // namespace facial
