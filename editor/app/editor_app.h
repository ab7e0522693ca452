#pragma once
// facial-editor: the face in a window with four panels around it (state
// machine and control map on the left, RBF sculpt on the right, the timeline
// along the bottom). The face sits in the free middle of the window.
#include <string>
#include <vector>

#include "app/program_error.h"

namespace editor {

// How the editor reports a failure: "facial-editor: error: ..." on stderr, exit code 1.
inline constexpr app::ErrorReporter fail{"facial-editor"};

struct EditorOptions {
  std::string model;     // empty: the built-in head
  std::string rigmap;    // empty: data/rigmaps/<model>.json or the detected scheme
  bool noAutorig = false;  // refuse a face that cannot show emotions (app::FaceSetupOptions::autorig)
  std::vector<std::string> shapes;  // --shape NAME=VALUE identity parameters (CANDIDE-3 shape units)
  std::string graph;     // empty: data/graphs/tour.json
  std::string timeline;  // opened in the timeline panel when given
  std::string device;    // Vulkan device (discrete | integrated | cpu | name); empty: FACIAL_DEVICE / automatic
  std::string size = "1280x800";
  std::string quality = "auto";  // render quality tier: auto | fast | balanced | high (app::windowQualityOption)
  std::string trigger;   // fired on the state machine at start
  float quitAfter = 0.0f;
  bool profile = false;  // print where the frames' time went on exit (app::WindowLoopOptions)
  std::string screenshot;  // written on the last frame (with --quit-after) or on F12
  std::string script;      // timed actions (editor_script.h)
  bool mute = false;       // Speak moves the mouth without playing the voice
  std::string project;     // opened at start (its model, rig map and graph are loaded with the face)
  // A project opened on another face goes on in a new editor (runEditor): the script from this action, its clock from this time.
  size_t scriptFrom = 0;
  float scriptClockFrom = 0.0f;
};

int runEditor(const EditorOptions& options);

}  // namespace editor
