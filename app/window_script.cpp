#include "app/window_script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace app {
namespace {

struct Verb {
  std::string_view word;
  ScriptAction::Kind kind;
  int numbers;  // arguments after the word (Trigger, SayLanguage: one name instead; Say: the rest of the line)
};
constexpr Verb kVerbs[] = {
    {"trigger", ScriptAction::Kind::Trigger, 0},  {"intensity", ScriptAction::Kind::Intensity, 1},
    {"pad", ScriptAction::Kind::Pad, 2},          {"graph", ScriptAction::Kind::Graph, 0},
    {"orbit", ScriptAction::Kind::Orbit, 2},      {"screenshot", ScriptAction::Kind::Screenshot, 0},
    {"resize", ScriptAction::Kind::Resize, 2},    {"iconify", ScriptAction::Kind::Iconify, 0},
    {"restore", ScriptAction::Kind::Restore, 0},  {"frame", ScriptAction::Kind::Frame, 0},
    {"say", ScriptAction::Kind::Say, 0},          {"say-lang", ScriptAction::Kind::SayLanguage, 0},
    {"say-stop", ScriptAction::Kind::SayStop, 0},
};

bool takesName(ScriptAction::Kind kind) {
  return kind == ScriptAction::Kind::Trigger || kind == ScriptAction::Kind::SayLanguage;
}

bool parseFloat(const std::string& word, float& value) {
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

}  // namespace

bool parseScriptNumber(const std::string& word, float& value) { return parseFloat(word, value); }

eng::Result<std::vector<TimedScriptLine>> splitTimedScript(std::string_view text, std::string_view source) {
  std::vector<TimedScriptLine> lines;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    auto fail = [&](const std::string& problem) {
      return eng::makeError(eng::ErrorKind::Malformed, std::string(source) + ":" + std::to_string(number) + ": " + problem);
    };
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream wordsIn(line);
    std::vector<std::string> words;
    for (std::string w; wordsIn >> w;) words.push_back(w);
    if (words.empty()) continue;

    TimedScriptLine timed;
    timed.line = number;
    if (!parseFloat(words[0], timed.time) || timed.time < 0.0f)
      return fail("'" + words[0] + "' is not a time in seconds (a number >= 0)");
    if (!lines.empty() && timed.time < lines.back().time)
      return fail("time " + words[0] + " s comes before the previous action's");
    if (words.size() < 2) return fail("an action must follow the time");
    timed.words.assign(words.begin() + 1, words.end());
    lines.push_back(std::move(timed));
  }
  return lines;
}

eng::Result<std::string> readScriptFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot open the script");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

eng::Result<std::vector<ScriptAction>> parseWindowScript(std::string_view text, std::string_view source) {
  auto lines = splitTimedScript(text, source);
  if (!lines) return lines.error();
  std::vector<ScriptAction> actions;
  for (const TimedScriptLine& timed : *lines) {
    auto fail = [&](const std::string& problem) {
      return eng::makeError(eng::ErrorKind::Malformed, std::string(source) + ":" + std::to_string(timed.line) + ": " + problem);
    };
    const std::vector<std::string>& words = timed.words;  // the action, then its arguments
    ScriptAction action;
    action.time = timed.time;
    const Verb* verb = nullptr;
    for (const Verb& v : kVerbs)
      if (v.word == words[0]) verb = &v;
    if (!verb)
      return fail("unknown action '" + words[0] +
                  "' (trigger, intensity, pad, graph, orbit, screenshot, resize, iconify, restore, say, say-lang, "
                  "say-stop)");
    action.kind = verb->kind;
    if (action.kind == ScriptAction::Kind::Say) {
      if (words.size() < 2) return fail("'say' needs the text to speak");
      for (size_t w = 1; w < words.size(); ++w) action.name += (w > 1 ? " " : "") + words[w];
      actions.push_back(std::move(action));
      continue;
    }
    const size_t wanted = 1 + (takesName(verb->kind) ? 1 : verb->numbers);
    if (words.size() != wanted)
      return fail("'" + words[0] + "' takes " + std::to_string(wanted - 1) + " argument(s), got " +
                  std::to_string(words.size() - 1));
    if (takesName(verb->kind)) {
      action.name = words[1];
    } else {
      float* values[] = {&action.a, &action.b};
      for (int i = 0; i < verb->numbers; ++i)
        if (!parseFloat(words[1 + i], *values[i])) return fail("'" + words[1 + i] + "' is not a finite number");
    }
    if (action.kind == ScriptAction::Kind::Intensity && (action.a < 0.0f || action.a > 1.0f))
      return fail("intensity " + words[1] + " is outside [0, 1]");
    if (action.kind == ScriptAction::Kind::Pad && (std::abs(action.a) > 1.0f || std::abs(action.b) > 1.0f))
      return fail("pad " + words[1] + " " + words[2] + " is outside [-1, 1]^2");
    if (action.kind == ScriptAction::Kind::Resize &&
        (action.a < 1.0f || action.b < 1.0f || action.a > 16384.0f || action.b > 16384.0f ||
         action.a != std::floor(action.a) || action.b != std::floor(action.b)))
      return fail("resize " + words[1] + " " + words[2] + " is not a whole size of 1..16384 per side");
    actions.push_back(std::move(action));
  }
  return actions;
}

eng::Result<std::vector<ScriptAction>> loadWindowScript(const std::filesystem::path& path) {
  auto text = readScriptFile(path);
  if (!text) return text.error();
  return parseWindowScript(*text, path.string());
}

}  // namespace app
