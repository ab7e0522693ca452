#include "editor/app/editor_script.h"

#include <cmath>

#include "app/window_script.h"
#include "editor/graph_document.h"
#include "editor/curve_model.h"
#include "facial/runtime/rig/emotions.h"

namespace editor {

namespace {

using Kind = EditorScriptAction::Kind;

struct Verb {
  std::string_view word;
  Kind kind;
  // Arguments: 'w' a word (name or path), 'n' a number, 't' the rest of the line
  // (one or more words, as one text), '*' any number of further words (into
  // `words`); those after '?' may be left out.
  std::string_view arguments;
};
constexpr Verb kVerbs[] = {
    {"trigger", Kind::Trigger, "w"},
    {"pad", Kind::Pad, "nn"},
    {"orbit", Kind::Orbit, "nn"},
    {"zoom", Kind::Zoom, "n"},
    {"timeline-open", Kind::TimelineOpen, "w"},
    {"timeline-seek", Kind::TimelineSeek, "n"},
    {"timeline-key-all", Kind::TimelineKeyAll, ""},
    {"timeline-key", Kind::TimelineKey, "w"},
    {"timeline-move-selected", Kind::TimelineMoveSelected, "nn"},
    {"timeline-delete", Kind::TimelineDelete, ""},
    {"undo", Kind::Undo, ""},
    {"redo", Kind::Redo, ""},
    {"timeline-save", Kind::TimelineSave, "w"},
    {"sculpt-pick", Kind::SculptPick, "nn"},
    {"sculpt-landmark", Kind::SculptLandmark, "w"},
    {"sculpt-move", Kind::SculptMove, "nnn"},
    {"sculpt-drag", Kind::SculptDrag, "nn"},
    {"sculpt-kernel", Kind::SculptKernel, "w?n"},
    {"sculpt-falloff", Kind::SculptFalloff, "n"},
    {"sculpt-bake", Kind::SculptBake, "w"},
    {"sculpt-save", Kind::SculptSave, "w"},
    {"landmarks-show", Kind::LandmarksShow, ""},
    {"landmark-move", Kind::LandmarkMove, "nnn"},
    {"autorig-rerun", Kind::AutorigRerun, ""},
    {"landmarks-save", Kind::LandmarksSave, ""},
    {"say", Kind::Say, "t"},
    {"say-lang", Kind::SayLanguage, "w"},
    {"say-stop", Kind::SayStop, ""},
    {"screenshot", Kind::Screenshot, "?w"},
    {"quit", Kind::Quit, ""},
    // Projects and export.
    {"project-new", Kind::ProjectNew, ""},
    {"project-open", Kind::ProjectOpen, "w"},
    {"project-save", Kind::ProjectSave, "?w"},
    {"project-save-as", Kind::ProjectSaveAs, "w"},
    {"export-glb", Kind::ExportGlb, "w"},
    {"export-gif", Kind::ExportGif, "w?w"},
    {"export-video", Kind::ExportVideo, "w?w"},
    {"quit-discard", Kind::QuitDiscard, ""},
    {"quit-save", Kind::QuitSave, ""},
    // The state machine diagram and the pads that record.
    {"graph-add-state", Kind::GraphAddState, "w?w"},
    {"graph-remove-state", Kind::GraphRemoveState, "w"},
    {"graph-rename-state", Kind::GraphRenameState, "ww"},
    {"graph-add-transition", Kind::GraphAddTransition, "wwwnw"},
    {"graph-edit-transition", Kind::GraphEditTransition, "wwnwww"},
    {"graph-save", Kind::GraphSave, "w"},
    {"bilinear-pad", Kind::BilinearPad, "nn"},
    {"record-start", Kind::RecordStart, ""},
    {"record-stop", Kind::RecordStop, ""},
    // Dope sheet and curve view (issue 34).
    {"timeline-box-select", Kind::TimelineBoxSelect, "nn*"},
    {"timeline-copy", Kind::TimelineCopy, ""},
    {"timeline-paste", Kind::TimelinePaste, "n"},
    {"timeline-duplicate", Kind::TimelineDuplicate, ""},
    {"timeline-nudge", Kind::TimelineNudge, "n"},
    {"timeline-snap", Kind::TimelineSnap, "n"},
    {"timeline-loop", Kind::TimelineLoop, "nn"},
    {"timeline-speed", Kind::TimelineSpeed, "n"},
    {"timeline-mute", Kind::TimelineMute, "w"},
    {"timeline-solo", Kind::TimelineSolo, "w"},
    {"curve-tangent", Kind::CurveTangent, "wnw?nn"},
    {"timeline-key-emotion", Kind::TimelineKeyEmotion, "wnw"},
    {"timeline-play", Kind::TimelinePlay, ""},
    {"timeline-pause", Kind::TimelinePause, ""},
};

// The dope sheet's and curve view's own checks ("" when fine).
std::string dopeSheetProblem(const EditorScriptAction& action) {
  switch (action.kind) {
    case Kind::TimelineNudge:
      if (action.a != std::round(action.a)) return "timeline-nudge takes whole frames";
      break;
    case Kind::TimelineSnap:
      if (action.a < 1.0f || action.a > 1000.0f) return "timeline-snap: 1 to 1000 frames a second";
      break;
    case Kind::TimelineLoop:
      if (!(action.a >= 0.0f && action.b > action.a)) return "timeline-loop: the end must come after the start (>= 0)";
      break;
    case Kind::TimelineSpeed:
      if (action.a < 0.05f || action.a > 20.0f) return "timeline-speed: 0.05 to 20";
      break;
    case Kind::Zoom:
      if (action.a < kMinViewZoom || action.a > kMaxViewZoom) return "zoom: 0.3 to 8";
      break;
    case Kind::CurveTangent:
      if (action.a < 0.0f || action.a != std::round(action.a)) return "curve-tangent: the key index is a whole number from 0";
      if (action.numberCount == 2) return "curve-tangent: give both slopes IN OUT, or neither";
      if (!curveKeyModeFromName(action.words[1]))
        return "unknown tangent mode '" + action.words[1] + "' (" + eng::nameList(kCurveKeyModeNames) + ")";
      break;
    case Kind::TimelineKeyEmotion:
      if (!facial::emotionIndex(action.words[0]))
        return "unknown emotion '" + action.words[0] + "' (" + facial::emotionNameList() + ")";
      if (!curveKeyModeFromName(action.words[1]))
        return "unknown easing '" + action.words[1] + "' (" + eng::nameList(kCurveKeyModeNames) + ")";
      break;
    default: break;
  }
  return {};
}

std::string verbList() {
  std::string list;
  for (const Verb& v : kVerbs) list += (list.empty() ? "" : ", ") + std::string(v.word);
  return list;
}

// The diagram's and the bilinear pad's arguments; "" when they are good (and for other actions).
// graph-edit-transition keeps its exit time in b (NaN: none) and the interruption rule in c (1: yes).
std::string checkGraphOrPadAction(EditorScriptAction& action) {
  if (action.kind != Kind::BilinearPad && action.kind != Kind::GraphAddTransition && action.kind != Kind::GraphEditTransition)
    return "";
  if (action.kind == Kind::BilinearPad)
    return action.a < 0.0f || action.a > 1.0f || action.b < 0.0f || action.b > 1.0f ? "bilinear-pad s, t must lie in [0, 1]" : "";
  const std::string& easing = action.kind == Kind::GraphAddTransition ? action.words[3] : action.words[2];
  if (auto timing = checkTransitionTiming(action.a, easing); !timing) return timing.error().message;
  if (action.kind == Kind::GraphAddTransition) return "";
  const std::string& exit = action.words[3];
  if (exit == "-") {
    action.b = NAN;
  } else if (!app::parseScriptNumber(exit, action.b) || action.b < 0.0f) {
    return "exit time '" + exit + "' is not a number of seconds >= 0 (or '-': none)";
  }
  const std::string& interrupt = action.words[4];
  if (interrupt != "yes" && interrupt != "no") return "interruption rule '" + interrupt + "' is not yes or no";
  action.c = interrupt == "yes" ? 1.0f : 0.0f;
  return "";
}

// What is wrong with an action's arguments (their values, once parsed), or "".
std::string argumentProblem(const EditorScriptAction& action, const std::vector<std::string>& words) {
  switch (action.kind) {
    case Kind::Pad:
      if (std::abs(action.a) > 1.0f || std::abs(action.b) > 1.0f)
        return "pad " + words[1] + " " + words[2] + " is outside [-1, 1]^2";
      break;
    case Kind::TimelineSeek:
      if (action.a < 0.0f) return "timeline-seek " + words[1] + " is before 0 s";
      break;
    case Kind::SculptPick:
      if (action.a < 0.0f || action.b < 0.0f) return "sculpt-pick " + words[1] + " " + words[2] + " is not a window pixel";
      break;
    case Kind::SculptKernel:
      if (action.text != "biharmonic" && action.text != "polyharmonic" && action.text != "multiquadric")
        return "unknown kernel '" + action.text + "' (biharmonic, polyharmonic, multiquadric)";
      if (action.text != "multiquadric" && action.hasNumber)
        return "only the multiquadric kernel takes a shape parameter c";
      if (action.hasNumber && action.a <= 0.0f) return "multiquadric c " + words[2] + " must be > 0";
      break;
    case Kind::LandmarkMove:
      if (action.a < 0.0f || action.a > 67.0f || action.a != std::floor(action.a))
        return "landmark-move " + words[1] + " is not a landmark index (0-67)";
      break;
    case Kind::SculptFalloff:
      if (action.a < 0.0f) return "sculpt-falloff " + words[1] + " must be >= 0 (0 = off)";
      break;
    default: break;
  }
  return {};
}

// The words after the action into `action` by `spec` ('w' text and words,
// 'n' numbers a, b, c, '*' the rest into words); a problem, or "".
std::string readArguments(std::string_view spec, const std::vector<std::string>& words, EditorScriptAction& action) {
  float* numbers[] = {&action.a, &action.b, &action.c};
  size_t nextNumber = 0;
  size_t argument = 1;
  for (const char type : spec) {
    if (type == '?') continue;
    if (argument >= words.size()) break;
    if (type == '*') {
      action.words.insert(action.words.end(), words.begin() + std::ptrdiff_t(argument), words.end());
      break;
    }
    const std::string& word = words[argument++];
    if (type == 'w') {
      if (action.words.empty()) action.text = word;  // text: the first word
      action.words.push_back(word);
    } else {
      if (!app::parseScriptNumber(word, *numbers[nextNumber])) return "'" + word + "' is not a finite number";
      ++nextNumber;
    }
  }
  action.hasNumber = nextNumber > 0;
  action.numberCount = nextNumber;
  return {};
}

}  // namespace

const char* editorScriptActionWord(Kind kind) {
  for (const Verb& v : kVerbs)
    if (v.kind == kind) return v.word.data();
  return "?";
}

eng::Result<std::vector<EditorScriptAction>> parseEditorScript(std::string_view text, std::string_view source) {
  auto lines = app::splitTimedScript(text, source);
  if (!lines) return lines.error();
  std::vector<EditorScriptAction> actions;
  for (const app::TimedScriptLine& timed : *lines) {
    const std::string where = std::string(source) + ":" + std::to_string(timed.line) + ": ";
    auto fail = [&](const std::string& problem) { return eng::makeError(eng::ErrorKind::Malformed, where + problem); };
    const std::vector<std::string>& words = timed.words;
    const Verb* verb = nullptr;
    for (const Verb& v : kVerbs)
      if (v.word == words[0]) verb = &v;
    if (!verb) return fail("unknown action '" + words[0] + "' (" + verbList() + ")");

    const std::string_view spec = verb->arguments;
    const bool restIsWords = !spec.empty() && spec.back() == '*';
    const std::string_view counted = restIsWords ? spec.substr(0, spec.size() - 1) : spec;
    const size_t optionalAt = counted.find('?');
    const size_t required = optionalAt == std::string_view::npos ? counted.size() : optionalAt;
    const size_t most = counted.size() - (optionalAt == std::string_view::npos ? 0 : 1);
    const bool restIsText = spec == "t";
    const size_t given = words.size() - 1;
    if (given < required || (given > most && !restIsText && !restIsWords))
      return fail("'" + words[0] + "' takes " +
                  (required == most ? std::to_string(most) : std::to_string(required) + " or " + std::to_string(most)) +
                  " argument(s), got " + std::to_string(given));

    EditorScriptAction action;
    action.time = timed.time;
    action.line = timed.line;
    action.kind = verb->kind;
    for (const std::string& w : words) action.written += (action.written.empty() ? "" : " ") + w;
    action.source = where + action.written;
    if (restIsText) {
      action.text = action.written.substr(words[0].size() + 1);
      actions.push_back(std::move(action));
      continue;
    }
    if (const std::string problem = readArguments(spec, words, action); !problem.empty()) return fail(problem);
    if (const std::string problem = dopeSheetProblem(action); !problem.empty()) return fail(problem);
    if (const std::string problem = argumentProblem(action, words); !problem.empty()) return fail(problem);
    if (auto problem = checkGraphOrPadAction(action); !problem.empty()) return fail(problem);
    actions.push_back(std::move(action));
  }
  return actions;
}

eng::Result<std::vector<EditorScriptAction>> loadEditorScript(const std::filesystem::path& path) {
  auto text = app::readScriptFile(path);
  if (!text) return text.error();
  return parseEditorScript(*text, path.string());
}

}  // namespace editor
