#pragma once
// An editor project: one JSON file that says what a piece of work is made of,
// so New / Open / Save / Save As bring all of it back at once:
//
//   {"version": 1,
//    "model": "faces/anna.glb", "rigmap": "", "graph": "graphs/anna.json",
//    "clips": [{"name": "hello", "file": "anna.clips/hello.json",
//               "settings": {"fps": 24, "speed": 0.5, "loop": [0.5, 2], "muted": ["AU12"], "solo": []}}],
//    "sculpt": {"file": "anna.sculpt.glb", "targets": [{"name": "smirk", "weight": 1}]},
//    "view": {"yaw": 10, "pitch": -5, "zoom": 1.2, "framing": "face"}}
//
// Paths are stored relative to the project's folder (the project moves with
// its files) and read back as paths the program can open; "" is the default
// (the built-in head, the detected rig, data/graphs/tour.json). The clips are
// timeline files (timeline_json.h) beside the project, so `facial play` plays
// them as they are; the sculpted expressions are the model with its baked
// targets, a .glb beside it. Plain C++: no window, unit-tested.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "editor/timeline_document.h"
#include "engine/core/result.h"
#include "facial/runtime/json/json_document.h"

namespace editor {

inline constexpr int kProjectFileVersion = 1;

struct ProjectClip {
  std::string name;
  std::filesystem::path file;  // timeline JSON
  // The editor's settings for it (frame rate, loop range, speed, mute / solo), which the timeline file does not hold.
  TimelineSettings settings;
};

struct ProjectSculptTarget {
  std::string name;     // a morph target baked in the editor
  float weight = 1.0f;  // its slider in the sculpt panel
};

struct ProjectView {
  float yawDegrees = 0.0f;
  float pitchDegrees = 0.0f;
  float zoom = 1.0f;
  bool wholeModel = false;  // F: the whole model instead of the head
  bool operator==(const ProjectView&) const = default;
};

struct Project {
  std::filesystem::path model;   // empty: the built-in head
  std::filesystem::path rigmap;  // empty: detected
  std::filesystem::path graph;   // empty: data/graphs/tour.json
  std::vector<ProjectClip> clips;
  std::filesystem::path sculptModel;  // the model with the baked targets; empty: nothing baked
  std::vector<ProjectSculptTarget> sculptTargets;
  ProjectView view;
};

// Where a project's own files go, beside it: "<dir>/<stem>.clips/<clip>.json",
// "<dir>/<stem>.sculpt.glb" and an edited graph "<dir>/<stem>.graph.json" (the stem without ".json").
std::filesystem::path projectClipPath(const std::filesystem::path& project, const std::string& clipName);
std::filesystem::path projectSculptPath(const std::filesystem::path& project);
std::filesystem::path projectGraphPath(const std::filesystem::path& project);

// `project` names the file, for the relative paths.
facial::Json projectToJson(const Project& data, const std::filesystem::path& project);
// Errors read "/clips/0/file: problem"; paths come back resolved against the project's folder.
eng::Result<Project> projectFromJson(const facial::Json& json, const std::filesystem::path& project);
// Errors name the file: "anna.json: /view/zoom: expected a number, got string".
eng::Result<Project> loadProject(const std::filesystem::path& path);
// Through a temporary sibling: a failed save leaves the old file.
eng::Result<void> saveProject(const Project& data, const std::filesystem::path& path);

// The recently opened projects, newest first, at most kMax, in
// $XDG_CONFIG_HOME/facial/recent.json (else ~/.config/facial/recent.json).
class RecentProjects {
 public:
  static constexpr size_t kMax = 10;
  // Empty when neither XDG_CONFIG_HOME nor HOME is set.
  static std::filesystem::path defaultFile();

  explicit RecentProjects(std::filesystem::path file = defaultFile()) : file_(std::move(file)) {}
  // Reads the list; a missing file is an empty list, a broken one an error naming it (the list stays empty).
  eng::Result<void> load();
  // Puts `project` (made absolute) first and writes the list.
  eng::Result<void> add(const std::filesystem::path& project);
  const std::vector<std::filesystem::path>& paths() const { return paths_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::vector<std::filesystem::path> paths_;
};

}  // namespace editor
