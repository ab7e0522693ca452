// facial-editor [--project P.json] [--model M.glb] [--rigmap map.json] [--graph G.json] [--timeline T.json]
//               [--quit-after S] [--screenshot out.png] [--script actions.txt] [--device D]
#include <CLI/CLI.hpp>

#include "app/face_setup.h"
#include "app/output_paths.h"
#include "app/program_error.h"
#include "app/view_options.h"
#include "editor/app/editor_app.h"

int main(int argc, char** argv) {
  editor::EditorOptions o;
  CLI::App app{"facial-editor: edit keyframe timelines, drive the state machine and the control map, "
               "and sculpt expressions with RBF control points"};
  app::addFaceOptions(app, o.model, o.rigmap, o.noAutorig);
  app::addShapeOption(app, o.shapes);
  app.add_option("--graph", o.graph, "Animation graph with a state machine (default: data/graphs/tour.json)");
  app.add_option("--timeline", o.timeline, "Timeline JSON to open in the timeline panel");
  app.add_option("--project", o.project,
                 "Project to open (JSON: model, rig map, graph, clips, sculpted expressions, view); its model, rig map "
                 "and graph replace --model, --rigmap and --graph");
  app.add_option("--device", o.device, "Vulkan device: discrete, integrated, cpu or a name substring");
  app.add_option("--size", o.size, "Window size WxH")->capture_default_str();
  app::addWindowQualityOption(app, o.quality);
  app.add_option("--trigger", o.trigger, "Fire this state machine trigger at start (e.g. happy)");
  app.add_option("--quit-after", o.quitAfter, "Close after this many seconds of animation (tests; a script's clock, which lags wall time only below 10 frames/s)");
  app.add_option("--screenshot", o.screenshot, "Write the last frame here (with --quit-after); F12 writes one any time");
  app.add_option("--script", o.script,
                 "Timed actions through the panels' own handlers, one a line: SECONDS ACTION ARGS "
                 "(trigger, pad, timeline-*, undo, redo, sculpt-*, say, say-lang, say-stop, project-*, export-glb, export-gif, export-video, "
                 "screenshot, quit, quit-save, quit-discard; see docs/editor.md)");
  app.add_flag("--profile", o.profile, "On exit, print where the frames' time went (mean ms and share per stage)");
  app.add_flag("--mute", o.mute, "Speak moves the mouth without playing the voice");
  CLI11_PARSE(app, argc, argv);
  if (auto safe = app::checkOutputs({.inputs = {{"--model", o.model}, {"--rigmap", o.rigmap}, {"--graph", o.graph},
                                                {"--timeline", o.timeline}, {"--script", o.script},
                                                {"--project", o.project}},
                                     .outputs = {{"--screenshot", o.screenshot}}});
      !safe)
    return app::ErrorReporter{"facial-editor"}(safe.error().message);
  return editor::runEditor(o);
}
