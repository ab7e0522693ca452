// `facial demo`: the virtual-character demo, the README's main job. Opens a
// window when there is a display, else plays the scripted tour headless.
#include <cstdlib>
#include <memory>

#include "cli/command.h"
#include "app/view_options.h"
#include "cli/demo/demo_options.h"
#include "app/face_setup.h"
#include "app/output_paths.h"
#include "app/program_error.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::demo_command {
namespace {

bool hasDisplay() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

CommandRegistrar reg("demo", "The virtual character: a window, or the headless tour without a display",
                     [](CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  app::addFaceOptions(app, o->model, o->rigmap, o->noAutorig);
  app::addShapeOption(app, o->shapes);
  app.add_option("--graph", o->graph, "Animation graph (default: data/graphs/tour.json)");
  app.add_flag("--headless", o->headless, "Render the tour to files even when a display is present");
  app.add_option("--out,-o", o->out, "Headless output folder (default: out/demo-<date-time>)");
  app.add_option("--size", o->size, "Frame or window size WxH");
  app.add_option("--fps", o->fps, "Headless frame rate")->capture_default_str();
  app.add_option("--seconds", o->seconds, "Headless length in seconds (default: one full tour)");
  app::addFramingOption(app, o->frame);
  app.add_option("--clip", o->clip,
                 "Skeletal animation of the model to play under the face: its name, its index, or 'all' (loops)");
  app.add_option("--crowd", o->crowd, "N faces in a grid, each with its own state machine and random triggers");
  app::addDeviceOption(app, o->device);
  app::addWindowQualityOption(app, o->quality);
  app.add_option("--seed", o->seed, "Random seed (blinks, crowd triggers)")->capture_default_str();
  app.add_option("--quit-after", o->quitAfter, "Window: close after this many seconds of animation (tests; a script's clock, which lags wall time only below 10 frames/s)");
  app.add_option("--screenshot", o->screenshot,
                 "Window: write the last frame here before quitting (F12 screenshots go to the same folder)");
  app.add_option("--script", o->script,
                 "Window: timed actions, one per line 'SECONDS ACTION ARGS' (trigger NAME, intensity X, pad X Y, "
                 "graph, orbit YAW PITCH, screenshot, resize W H, iconify, restore, say TEXT, say-lang CODE, say-stop)");
  app.add_flag("--still", o->still, "Window: no idle sway, breathing or eye saccades (blinks stay)");
  app.add_flag("--mute", o->mute, "Window: Speak moves the mouth without playing the voice");
  return [o] {
    const std::string frames = o->out.empty() ? std::string() : (std::filesystem::path(o->out) / "frames").string();
    if (auto safe = app::checkOutputs({.inputs = {{"--model", o->model}, {"--rigmap", o->rigmap}, {"--graph", o->graph},
                                                  {"--script", o->script}},
                                       .outputs = {{"--screenshot", o->screenshot}},
                                       .frameFolders = {{"--out", frames}}});
        !safe)
      return app::ErrorReporter{"facial demo"}(safe.error().message);
    return (o->headless || !hasDisplay()) ? runHeadlessDemo(*o) : runWindowDemo(*o);
  };
});

}  // namespace
}  // namespace cli::demo_command
