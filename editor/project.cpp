#include "editor/project.h"

#include <algorithm>
#include <cstdlib>

#include "editor/atomic_file.h"
#include "facial/runtime/json/json_node.h"

namespace editor {

namespace fs = std::filesystem;

namespace {

fs::path folderOf(const fs::path& project) {
  const fs::path folder = fs::absolute(project).parent_path();
  return folder.empty() ? fs::current_path() : folder;
}

// Relative to the project's folder, so the project moves with its files.
std::string stored(const fs::path& path, const fs::path& project) {
  if (path.empty()) return "";
  return fs::absolute(path).lexically_proximate(folderOf(project)).generic_string();
}

eng::Result<fs::path> pathAt(const facial::JsonNode& object, std::string_view key, const fs::path& project) {
  const std::string text = ENG_TRY_VALUE(object.stringOr(key, ""));
  if (text.empty()) return fs::path();
  const fs::path path(text);
  return (path.is_absolute() ? path : folderOf(project) / path).lexically_normal();
}

eng::Result<std::vector<std::string>> readNames(const facial::JsonNode& j, std::string_view key) {
  std::vector<std::string> names;
  if (const auto list = j.find(key)) {
    const size_t count = ENG_TRY_VALUE(list->size());
    for (size_t i = 0; i < count; ++i) names.push_back(ENG_TRY_VALUE(list->element(i).string()));
  }
  return names;
}

eng::Result<TimelineSettings> readClipSettings(const facial::JsonNode& j) {
  ENG_TRY(j.allowOnly({"fps", "speed", "loop", "muted", "solo"}));
  TimelineSettings s;
  s.frameRate = ENG_TRY_VALUE(j.numberOr("fps", 30.0f));
  if (!(s.frameRate >= 1.0f && s.frameRate <= 1000.0f)) return j.error("fps " + facial::formatNumber(s.frameRate) + " must be 1 to 1000");
  s.playback.speed = ENG_TRY_VALUE(j.numberOr("speed", 1.0f));
  if (!(s.playback.speed >= 0.05f && s.playback.speed <= 20.0f))
    return j.error("speed " + facial::formatNumber(s.playback.speed) + " must be 0.05 to 20");
  if (const auto loop = j.find("loop")) {
    if (ENG_TRY_VALUE(loop->size()) != 2) return loop->error("expected [start, end] seconds");
    s.playback.hasLoopRange = true;
    s.playback.loopStart = ENG_TRY_VALUE(loop->element(0).number());
    s.playback.loopEnd = ENG_TRY_VALUE(loop->element(1).number());
    if (!(s.playback.loopStart >= 0.0f && s.playback.loopEnd > s.playback.loopStart))
      return loop->error("loop range must start at 0 or later and end after it");
  }
  s.muted = ENG_TRY_VALUE(readNames(j, "muted"));
  s.solo = ENG_TRY_VALUE(readNames(j, "solo"));
  return s;
}

facial::Json clipSettingsToJson(const TimelineSettings& s) {
  facial::Json json = {{"fps", s.frameRate}, {"speed", s.playback.speed}, {"muted", s.muted}, {"solo", s.solo}};
  if (s.playback.hasLoopRange) json["loop"] = {s.playback.loopStart, s.playback.loopEnd};
  return json;
}

eng::Result<ProjectClip> readClip(const facial::JsonNode& j, const fs::path& project) {
  ENG_TRY(j.allowOnly({"name", "file", "settings"}));
  ProjectClip clip;
  clip.name = ENG_TRY_VALUE(j.stringAt("name"));
  clip.file = ENG_TRY_VALUE(pathAt(j, "file", project));
  if (clip.file.empty()) return j.error("a clip needs its timeline \"file\"");
  if (const auto settings = j.find("settings")) clip.settings = ENG_TRY_VALUE(readClipSettings(*settings));
  return clip;
}

eng::Result<void> readSculpt(const facial::JsonNode& j, const fs::path& project, Project& out) {
  ENG_TRY(j.allowOnly({"file", "targets"}));
  out.sculptModel = ENG_TRY_VALUE(pathAt(j, "file", project));
  if (const auto targets = j.find("targets")) {
    const size_t count = ENG_TRY_VALUE(targets->size());
    for (size_t i = 0; i < count; ++i) {
      const facial::JsonNode t = targets->element(i);
      ENG_TRY(t.allowOnly({"name", "weight"}));
      ProjectSculptTarget target;
      target.name = ENG_TRY_VALUE(t.stringAt("name"));
      target.weight = ENG_TRY_VALUE(t.numberOr("weight", 1.0f));
      out.sculptTargets.push_back(std::move(target));
    }
  }
  if (!out.sculptTargets.empty() && out.sculptModel.empty()) return j.error("baked targets listed but no \"file\" holds them");
  return {};
}

eng::Result<ProjectView> readView(const facial::JsonNode& j) {
  ENG_TRY(j.allowOnly({"yaw", "pitch", "zoom", "framing"}));
  ProjectView view;
  view.yawDegrees = ENG_TRY_VALUE(j.numberOr("yaw", 0.0f));
  view.pitchDegrees = ENG_TRY_VALUE(j.numberOr("pitch", 0.0f));
  view.zoom = ENG_TRY_VALUE(j.numberOr("zoom", 1.0f));
  if (view.zoom <= 0.0f) return j.error("zoom " + facial::formatNumber(view.zoom) + " must be > 0");
  const std::string framing = ENG_TRY_VALUE(j.stringOr("framing", "face"));
  if (framing != "face" && framing != "all") return j.error("framing '" + framing + "' is not face or all");
  view.wholeModel = framing == "all";
  return view;
}

}  // namespace

fs::path projectClipPath(const fs::path& project, const std::string& clipName) {
  fs::path stem = project.filename();
  stem.replace_extension();
  // A clip name is a word from the user: only its file-name-safe characters.
  std::string file;
  for (const char c : clipName) file += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return project.parent_path() / (stem.string() + ".clips") / ((file.empty() ? "clip" : file) + ".json");
}

fs::path projectSculptPath(const fs::path& project) {
  fs::path stem = project.filename();
  stem.replace_extension();
  return project.parent_path() / (stem.string() + ".sculpt.glb");
}

fs::path projectGraphPath(const fs::path& project) {
  fs::path stem = project.filename();
  stem.replace_extension();
  return project.parent_path() / (stem.string() + ".graph.json");
}

facial::Json projectToJson(const Project& data, const fs::path& project) {
  facial::Json clips = facial::Json::array();
  for (const ProjectClip& clip : data.clips)
    clips.push_back({{"name", clip.name}, {"file", stored(clip.file, project)}, {"settings", clipSettingsToJson(clip.settings)}});
  facial::Json targets = facial::Json::array();
  for (const ProjectSculptTarget& t : data.sculptTargets) targets.push_back({{"name", t.name}, {"weight", t.weight}});
  return {{"version", kProjectFileVersion},
          {"model", stored(data.model, project)},
          {"rigmap", stored(data.rigmap, project)},
          {"graph", stored(data.graph, project)},
          {"clips", std::move(clips)},
          {"sculpt", {{"file", stored(data.sculptModel, project)}, {"targets", std::move(targets)}}},
          {"view",
           {{"yaw", data.view.yawDegrees},
            {"pitch", data.view.pitchDegrees},
            {"zoom", data.view.zoom},
            {"framing", data.view.wholeModel ? "all" : "face"}}}};
}

eng::Result<Project> projectFromJson(const facial::Json& json, const fs::path& project) {
  const facial::JsonNode root(json, "");
  ENG_TRY(facial::requireVersion(root, kProjectFileVersion));
  ENG_TRY(root.allowOnly({"version", "model", "rigmap", "graph", "clips", "sculpt", "view"}));
  Project data;
  data.model = ENG_TRY_VALUE(pathAt(root, "model", project));
  data.rigmap = ENG_TRY_VALUE(pathAt(root, "rigmap", project));
  data.graph = ENG_TRY_VALUE(pathAt(root, "graph", project));
  if (const auto clips = root.find("clips")) {
    const size_t count = ENG_TRY_VALUE(clips->size());
    for (size_t i = 0; i < count; ++i) data.clips.push_back(ENG_TRY_VALUE(readClip(clips->element(i), project)));
  }
  if (const auto sculpt = root.find("sculpt")) ENG_TRY(readSculpt(*sculpt, project, data));
  if (const auto view = root.find("view")) data.view = ENG_TRY_VALUE(readView(*view));
  return data;
}

eng::Result<Project> loadProject(const fs::path& path) {
  auto json = facial::readJsonFile(path);
  if (!json) return json.error();
  auto data = projectFromJson(*json, path);
  if (!data) return data.error().prefixed(path.string() + ": ");
  return data;
}

eng::Result<void> saveProject(const Project& data, const fs::path& path) { return writeJsonAtomically(projectToJson(data, path), path); }

fs::path RecentProjects::defaultFile() {
  if (const char* config = std::getenv("XDG_CONFIG_HOME"); config && *config) return fs::path(config) / "facial" / "recent.json";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".config" / "facial" / "recent.json";
  return {};
}

eng::Result<void> RecentProjects::load() {
  paths_.clear();
  std::error_code error;
  if (file_.empty() || !fs::exists(file_, error)) return {};
  auto json = facial::readJsonFile(file_);
  if (!json) return json.error();
  const facial::JsonNode root(*json, "");
  auto read = [&]() -> eng::Result<void> {
    const facial::JsonNode list = ENG_TRY_VALUE(root.at("projects"));
    const size_t count = ENG_TRY_VALUE(list.size());
    for (size_t i = 0; i < count && paths_.size() < kMax; ++i) paths_.emplace_back(ENG_TRY_VALUE(list.element(i).string()));
    return {};
  };
  if (auto ok = read(); !ok) {
    paths_.clear();
    return ok.error().prefixed(file_.string() + ": ");
  }
  return {};
}

eng::Result<void> RecentProjects::add(const fs::path& project) {
  const fs::path absolute = fs::absolute(project).lexically_normal();
  std::erase(paths_, absolute);
  paths_.insert(paths_.begin(), absolute);
  if (paths_.size() > kMax) paths_.resize(kMax);
  if (file_.empty()) return eng::makeError(eng::ErrorKind::NotFound, "no place for the recent projects list (neither XDG_CONFIG_HOME nor HOME is set)");
  std::error_code error;
  fs::create_directories(file_.parent_path(), error);
  if (error) return eng::makeError(eng::ErrorKind::Io, file_.parent_path().string() + ": cannot create the folder (" + error.message() + ")");
  facial::Json list = facial::Json::array();
  for (const fs::path& p : paths_) list.push_back(p.string());
  return writeJsonAtomically({{"projects", std::move(list)}}, file_);
}

}  // namespace editor
