#pragma once
// `facial-editor --script FILE`: timed actions that go through the same panel
// handlers as the buttons, keys and mouse, so a test, a demo or a batch bake
// can drive the whole editor. The line format (seconds, '#' comments, times in
// ascending order, errors "FILE:LINE: problem") is the window demo's
// (app/window_script.h); the actions are the editor's own:
//
//   0.5 trigger happy              a state machine trigger button
//   0.8 pad 0.7 -0.2               the control map pad's cursor ([-1, 1]^2)
//   1.0 orbit 20 -5                turn the camera (yaw / pitch degrees), as a drag in the view
//   1.1 zoom 1.15                  the camera's zoom, as the wheel sets it (0.3 to 8; 1: the face framed)
//   1.2 timeline-open T.json       the timeline panel's Open
//   1.4 timeline-seek 0.5          scrub the playhead (the timeline drives the face)
//   1.5 timeline-key-all           "Key all": every track at the playhead, value on screen
//   1.6 timeline-key AU12          select the track, then "Key track"
//   1.7 timeline-move-selected 0.1 0.2   drag the selected keys by dt seconds and dv value
//   1.8 timeline-delete            the Delete key
//   1.9 undo / redo                Ctrl+Z / Ctrl+Y
//   2.0 timeline-save OUT.json     Save (through a temporary sibling)
//   2.2 sculpt-pick 600 280        a click on the face at that window pixel in pick mode
//   2.3 sculpt-landmark nose_tip   "Add landmark" (built-in head)
//   2.4 sculpt-move 0 0.01 0       the selected point's XYZ drags (model units)
//   2.5 sculpt-drag 40 -10         Shift+drag in the view by pixels (screen plane)
//   2.6 sculpt-kernel multiquadric 0.02   biharmonic | polyharmonic | multiquadric [c]
//   2.8 sculpt-bake smirk          Bake as a named morph target
//   3.0 sculpt-save OUT.glb        Save .glb
//   3.0 landmarks-show             the Landmarks panel's Show (the 68 points the face was rigged from)
//   3.0 landmark-move 48 6 -2      select landmark 48 and drag it by pixels in the view (over the skin)
//   3.0 autorig-rerun              "Re-run transfer": the face rigged again from the points as they are
//   3.0 landmarks-save             Save: <stem>.landmarks.json beside the face
//   3.0 say-lang vi                the Speak box's language (an espeak-ng voice; "en" until set)
//   3.1 say Xin chào các bạn!      the Speak box's text (the rest of the line) and Speak
//   3.15 say-stop                  its Stop button
//   3.2 screenshot shot.png        as F12 (no path: where F12 writes); later actions wait for it
//   3.5 quit                       close the window (the --screenshot frame is still written); unsaved
//                                  changes stay in the autosaves, as when the window is lost
//   Projects and export (the File menu):
//   4.0 project-new                New (unsaved changes stay in the autosaves)
//   4.1 project-open P.json        Open (and Recent); an autosave newer than the file is recovered
//   4.2 project-save [P.json]      Save (no path: the project's own file; a path: there, as Save As)
//   4.3 project-save-as P.json     Save As
//   4.4 export-glb OUT.glb         Export .glb: the face, its sculpted targets, every clip as an animation
//   4.5 export-gif OUT.gif [CLIP]  Export GIF: the clip (the one being edited, or the project's clip CLIP)
//   4.5 export-video OUT.mp4 [CLIP]  Export video: the same frames at 30 fps as H.264 MP4 (no sound)
//   4.6 quit-discard, quit-save    the unsaved-changes question on quit answered Discard / Save
//
// The state machine diagram and the pads that record (issue 34, points 3 and 4):
//   graph-add-state smirk [happy]         add a state (its pose: the preset, the state's name when left out)
//   graph-remove-state sad                remove a state and the transitions into it
//   graph-rename-state smirk grin         rename a state (transitions follow)
//   graph-add-transition FROM TO TRIGGER DURATION EASING   FROM may be "any"; TRIGGER "-": none
//   graph-edit-transition FROM TO DURATION EASING EXIT_TIME INTERRUPT   EXIT_TIME "-": none; INTERRUPT yes|no
//   graph-save OUT.json                   the diagram's Save (the graph file the runtime reads)
//   bilinear-pad 0.5 0.8                  the bilinear pad's cursor (s, t in [0, 1])
//   record-start / record-stop            Record: what the pads and sliders do becomes timeline keys
//
// The dope sheet and curve view (docs/editor.md, "Timeline" and "Curves"):
//   timeline-key-emotion happy 1.0 cosine   key an emotion at 1 over the others at 0, with an
//                                   easing: a curve key mode (auto smooth flat broken linear step cosine)
//   timeline-box-select 0.9 2.1 [TRACK...]  a box over those times (the tracks named, else all)
//   timeline-copy / timeline-paste 2.5 / timeline-duplicate   Ctrl+C / paste at that time / Ctrl+D
//   timeline-nudge -2              the arrow keys: the selection by whole frames
//   timeline-snap 24               the frame rate, and the selection (all keys if none) snapped to it
//   timeline-loop 0.5 2.0 / timeline-speed 0.5   the loop range, the playback speed
//   timeline-mute TRACK / timeline-solo TRACK    the track's M / S toggles
//   curve-tangent TRACK 2 smooth [IN OUT]        key 2 of the track (from 0) in the curve view: its
//                                   mode, and slopes (value per second; smooth takes OUT, broken both)
//
// Paths are one word (no spaces), relative to the working folder. An action
// that fails at run time (a pick that misses, a save that cannot write) is
// reported like the button's failure, the script goes on, and the program
// exits with status 1.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace editor {

// The view camera's zoom range (the wheel, the zoom action, a project's view).
inline constexpr float kMinViewZoom = 0.3f, kMaxViewZoom = 8.0f;

struct EditorScriptAction {
  enum class Kind {
    Trigger, Pad, Orbit, Zoom,
    TimelineOpen, TimelineSeek, TimelineKeyAll, TimelineKey, TimelineMoveSelected, TimelineDelete, Undo, Redo, TimelineSave,
    SculptPick, SculptLandmark, SculptMove, SculptDrag, SculptKernel, SculptFalloff, SculptBake, SculptSave,
    LandmarksShow, LandmarkMove, AutorigRerun, LandmarksSave,
    Say, SayLanguage, SayStop,
    Screenshot, Quit,
    GraphAddState, GraphRemoveState, GraphRenameState, GraphAddTransition, GraphEditTransition, GraphSave,
    BilinearPad, RecordStart, RecordStop,
    // Projects and export (File menu; editor/app/project_actions.h).
    ProjectNew, ProjectOpen, ProjectSave, ProjectSaveAs, ExportGlb, ExportGif, ExportVideo, QuitDiscard, QuitSave,
    // Dope sheet and curve view (issue 34): TimelinePanel::runScriptAction runs these.
    TimelineBoxSelect, TimelineCopy, TimelinePaste, TimelineDuplicate, TimelineNudge, TimelineSnap, TimelineLoop,
    TimelineSpeed, TimelineMute, TimelineSolo, CurveTangent, TimelineKeyEmotion, TimelinePlay, TimelinePause,
  };
  float time = 0.0f;
  int line = 0;
  Kind kind = Kind::Quit;
  std::string text;                      // the name, path or text argument ("" when none)
  float a = 0.0f, b = 0.0f, c = 0.0f;   // the numeric arguments, in order
  bool hasNumber = false;                // sculpt-kernel: c was given
  std::vector<std::string> words;        // every word argument, in order (text is the first; '*': the rest of the line's words)
  size_t numberCount = 0;                // how many numbers were given
  std::string written;                   // "ACTION ARGS" as in the file
  std::string source;                    // "FILE:LINE: ACTION ARGS" for messages
};

const char* editorScriptActionWord(EditorScriptAction::Kind kind);

eng::Result<std::vector<EditorScriptAction>> parseEditorScript(std::string_view text, std::string_view source);
eng::Result<std::vector<EditorScriptAction>> loadEditorScript(const std::filesystem::path& path);

}  // namespace editor
