#include "app/presenter_script.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "app/window_script.h"
#include "facial/runtime/json/json_document.h"
#include "facial/runtime/json/json_node.h"
#include "facial/runtime/rig/emotions.h"

namespace app {
namespace {

constexpr auto kMalformed = eng::ErrorKind::Malformed;

eng::Result<float> intensityFrom(const std::string& word) {
  float value = 0;
  if (!parseScriptNumber(word, value) || value < 0.0f || value > 1.0f)
    return eng::makeError(kMalformed, "intensity '" + word + "' is not a number in [0, 1]");
  return value;
}

eng::Result<float> pauseFrom(const std::string& word) {
  float value = 0;
  if (!parseScriptNumber(word, value) || value < 0.0f || value > kMaxScriptPauseSeconds)
    return eng::makeError(kMalformed, "pause '" + word + "' is not a number of seconds in [0, 60]");
  return value;
}

// Builds the segments line by line. Errors carry the bare problem; the caller
// says where (a line number or a JSON pointer).
class ScriptBuilder {
 public:
  explicit ScriptBuilder(const ScriptDefaults& defaults)
      : emotion_(defaults.emotion), intensity_(defaults.intensity), defaultIntensity_(defaults.intensity) {}

  // Text with tags; ends with the line pause.
  eng::Result<void> readLine(std::string_view line, int number) {
    size_t at = 0;
    while (at < line.size()) {
      const size_t open = line.find_first_of("[]", at);
      say(line.substr(at, open == std::string_view::npos ? std::string_view::npos : open - at), number);
      if (open == std::string_view::npos) break;
      if (line[open] == ']') return eng::makeError(kMalformed, "']' without its '['");
      const size_t close = line.find_first_of("[]", open + 1);
      if (close == std::string_view::npos || line[close] == '[')
        return eng::makeError(kMalformed, "'[' is not closed by ']'");
      ENG_TRY(readTag(line.substr(open + 1, close - open - 1)));
      at = close + 1;
    }
    implicitPause_ = std::max(implicitPause_, kLinePauseSeconds);
    return {};
  }
  void paragraph() { implicitPause_ = std::max(implicitPause_, kParagraphPauseSeconds); }
  eng::Result<void> setEmotion(const std::string& name, float intensity) {
    if (!facial::emotionIndex(name)) return eng::makeError(kMalformed, "unknown emotion '" + name + "' (known: " + facial::emotionNameList() + ")");
    emotion_ = name;
    intensity_ = intensity;
    return {};
  }
  // Replaces the line's own pause: "[pause 0]" joins two lines.
  void pause(float seconds) {
    explicitPause_ = explicit_ ? explicitPause_ + seconds : seconds;
    explicit_ = true;
  }
  float defaultIntensity() const { return defaultIntensity_; }

  eng::Result<PresenterScript> finish() && {
    if (script_.segments.empty()) return eng::makeError(kMalformed, "the script says nothing (no text to speak)");
    return std::move(script_);
  }

 private:
  eng::Result<void> readTag(std::string_view tag) {
    std::istringstream in{std::string(tag)};
    std::vector<std::string> words{std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
    if (words.empty()) return eng::makeError(kMalformed, "empty tag '[]' (an emotion or pause)");
    std::string name = words[0];
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (words.size() > 2) return eng::makeError(kMalformed, "tag '[" + std::string(tag) + "]' has more than one number");
    if (name == "pause") {
      if (words.size() != 2) return eng::makeError(kMalformed, "[pause] needs its seconds, e.g. [pause 1.5]");
      pause(ENG_TRY_VALUE(pauseFrom(words[1])));
      return {};
    }
    if (!facial::emotionIndex(name))
      return eng::makeError(kMalformed, "unknown tag '[" + std::string(tag) + "]': not pause or an emotion (" + facial::emotionNameList() + ")");
    return setEmotion(name, words.size() == 2 ? ENG_TRY_VALUE(intensityFrom(words[1])) : defaultIntensity_);
  }

  void say(std::string_view piece, int line) {
    std::istringstream in{std::string(piece)};
    std::string text;
    for (std::string word; in >> word;) text += (text.empty() ? "" : " ") + word;
    if (text.empty()) return;
    const float silence = explicit_ ? explicitPause_ : implicitPause_;
    if (!script_.segments.empty() && silence > 0.0f)
      script_.segments.push_back({.kind = ScriptSegment::Kind::Pause, .seconds = silence, .line = line});
    script_.segments.push_back({.kind = ScriptSegment::Kind::Speech, .text = std::move(text), .emotion = emotion_,
                                .intensity = intensity_, .line = line});
    implicitPause_ = explicitPause_ = 0.0f;
    explicit_ = false;
  }

  PresenterScript script_;
  std::string emotion_;
  float intensity_;
  float defaultIntensity_;
  float implicitPause_ = 0.0f, explicitPause_ = 0.0f;
  bool explicit_ = false;
};

eng::Result<PresenterScript> finished(ScriptBuilder&& builder, const std::string& where) {
  auto script = std::move(builder).finish();
  if (!script) return script.error().prefixed(where);
  return script;
}

eng::Result<PresenterScript> parseTextScript(std::string_view text, std::string_view source, const ScriptDefaults& defaults) {
  ScriptBuilder builder(defaults);
  std::istringstream in{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
      builder.paragraph();
      continue;
    }
    if (line[first] == '#') continue;
    if (auto read = builder.readLine(line, number); !read)
      return read.error().prefixed(std::string(source) + ":" + std::to_string(number) + ": ");
  }
  return finished(std::move(builder), std::string(source) + ": ");
}

eng::Result<void> readJsonLine(const facial::JsonNode& j, int number, ScriptBuilder& builder) {
  ENG_TRY(j.allowOnly({"text", "emotion", "intensity", "pause"}));
  if (j.has("emotion") || j.has("intensity")) {
    std::string emotion = ENG_TRY_VALUE(j.stringOr("emotion", ""));
    const float intensity = ENG_TRY_VALUE(j.numberOr("intensity", builder.defaultIntensity()));
    if (intensity < 0.0f || intensity > 1.0f) return ENG_TRY_VALUE(j.at("intensity")).error("must be in [0, 1]");
    if (emotion.empty()) return j.error("\"intensity\" needs its \"emotion\"");
    if (auto set = builder.setEmotion(emotion, intensity); !set) return ENG_TRY_VALUE(j.at("emotion")).error(set.error());
  }
  const std::string text = ENG_TRY_VALUE(j.stringAt("text"));
  if (auto read = builder.readLine(text, number); !read) return ENG_TRY_VALUE(j.at("text")).error(read.error());
  if (j.has("pause")) {
    const float seconds = ENG_TRY_VALUE(j.numberAt("pause"));
    if (seconds < 0.0f || seconds > kMaxScriptPauseSeconds)
      return ENG_TRY_VALUE(j.at("pause")).error("must be a number of seconds in [0, 60]");
    builder.pause(seconds);
  }
  return {};
}

eng::Result<PresenterScript> parseJsonScript(std::string_view text, std::string_view source, const ScriptDefaults& defaults) {
  const std::string where = std::string(source) + ": ";
  auto document = facial::parseJsonText(text, source);
  if (!document) return document.error();
  const facial::JsonNode root(*document, "");
  ScriptBuilder builder(defaults);
  auto read = [&]() -> eng::Result<void> {
    ENG_TRY(root.allowOnly({"version", "lines"}));
    ENG_TRY(facial::checkFormatVersion(ENG_TRY_VALUE(root.at("version")).raw(), 1));
    const facial::JsonNode lines = ENG_TRY_VALUE(root.at("lines"));
    const size_t count = ENG_TRY_VALUE(lines.size());
    for (size_t i = 0; i < count; ++i) ENG_TRY(readJsonLine(lines.element(i), int(i) + 1, builder));
    return {};
  };
  if (auto done = read(); !done) return done.error().prefixed(where);
  return finished(std::move(builder), where);
}

}  // namespace

eng::Result<PresenterScript> parsePresenterScript(std::string_view text, std::string_view source,
                                                  const ScriptDefaults& defaults) {
  if (text.size() > kMaxPresenterScriptBytes)
    return eng::makeError(eng::ErrorKind::TooLarge, std::string(source) + ": " + std::to_string(text.size()) +
                                                        " bytes, over the script limit of 1 MB");
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && text[first] == '{') return parseJsonScript(text, source, defaults);
  return parseTextScript(text, source, defaults);
}

eng::Result<PresenterScript> loadPresenterScript(const std::filesystem::path& path, const ScriptDefaults& defaults) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec || std::filesystem::is_directory(path)) return eng::makeError(eng::ErrorKind::NotFound, path.string() + ": cannot open the script");
  if (bytes > kMaxPresenterScriptBytes)
    return eng::makeError(eng::ErrorKind::TooLarge, path.string() + ": " + std::to_string(bytes) +
                                                        " bytes, over the script limit of 1 MB");
  auto text = readScriptFile(path);
  if (!text) return text.error();
  return parsePresenterScript(*text, path.string(), defaults);
}

}  // namespace app
