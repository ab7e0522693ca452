#include "demo/window_script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace cli {
namespace {

struct Verb {
  std::string_view word;
  ScriptAction::Kind kind;
  int numbers;  // arguments after the word (Trigger: one name instead)
};
constexpr Verb kVerbs[] = {
    {"trigger", ScriptAction::Kind::Trigger, 0},  {"intensity", ScriptAction::Kind::Intensity, 1},
    {"pad", ScriptAction::Kind::Pad, 2},          {"graph", ScriptAction::Kind::Graph, 0},
    {"orbit", ScriptAction::Kind::Orbit, 2},      {"screenshot", ScriptAction::Kind::Screenshot, 0},
    {"resize", ScriptAction::Kind::Resize, 2},    {"iconify", ScriptAction::Kind::Iconify, 0},
    {"restore", ScriptAction::Kind::Restore, 0},
};

bool parseFloat(const std::string& word, float& value) {
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

}  // namespace

eng::Result<std::vector<ScriptAction>> parseWindowScript(std::string_view text, std::string_view source) {
  std::vector<ScriptAction> actions;
  std::istringstream lines{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    auto fail = [&](const std::string& problem) {
      return eng::makeError(std::string(source) + ":" + std::to_string(number) + ": " + problem);
    };
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (words.empty()) continue;

    ScriptAction action;
    if (!parseFloat(words[0], action.time) || action.time < 0.0f)
      return fail("'" + words[0] + "' is not a time in seconds (a number >= 0)");
    if (!actions.empty() && action.time < actions.back().time)
      return fail("time " + words[0] + " s comes before the previous action's");
    if (words.size() < 2) return fail("an action must follow the time");
    const Verb* verb = nullptr;
    for (const Verb& v : kVerbs)
      if (v.word == words[1]) verb = &v;
    if (!verb)
      return fail("unknown action '" + words[1] +
                  "' (trigger, intensity, pad, graph, orbit, screenshot, resize, iconify, restore)");
    action.kind = verb->kind;
    const size_t wanted = 2 + (verb->kind == ScriptAction::Kind::Trigger ? 1 : verb->numbers);
    if (words.size() != wanted)
      return fail("'" + words[1] + "' takes " + std::to_string(wanted - 2) + " argument(s), got " +
                  std::to_string(words.size() - 2));
    if (verb->kind == ScriptAction::Kind::Trigger) {
      action.name = words[2];
    } else {
      float* values[] = {&action.a, &action.b};
      for (int i = 0; i < verb->numbers; ++i)
        if (!parseFloat(words[2 + i], *values[i])) return fail("'" + words[2 + i] + "' is not a finite number");
    }
    if (action.kind == ScriptAction::Kind::Intensity && (action.a < 0.0f || action.a > 1.0f))
      return fail("intensity " + words[2] + " is outside [0, 1]");
    if (action.kind == ScriptAction::Kind::Pad && (std::abs(action.a) > 1.0f || std::abs(action.b) > 1.0f))
      return fail("pad " + words[2] + " " + words[3] + " is outside [-1, 1]^2");
    if (action.kind == ScriptAction::Kind::Resize &&
        (action.a < 1.0f || action.b < 1.0f || action.a > 16384.0f || action.b > 16384.0f ||
         action.a != std::floor(action.a) || action.b != std::floor(action.b)))
      return fail("resize " + words[2] + " " + words[3] + " is not a whole size of 1..16384 per side");
    actions.push_back(std::move(action));
  }
  return actions;
}

eng::Result<std::vector<ScriptAction>> loadWindowScript(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(path.string() + ": cannot open the script");
  std::stringstream text;
  text << in.rdbuf();
  return parseWindowScript(text.str(), path.string());
}

}  // namespace cli
