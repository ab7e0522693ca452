#pragma once
// The one thing panels know of the face on screen (ImSequencer style: the
// editor widgets talk to the model through a small interface and float time;
// none of them reaches into the renderer). The editor app implements it.
#include <cstdio>
#include <string>
#include <string_view>

namespace editor {

// Which panel poses the face this frame.
enum class FaceSource { StateMachine, ControlMap, Timeline, BilinearPad };
const char* faceSourceName(FaceSource source);

class FaceDelegate {
 public:
  virtual ~FaceDelegate() = default;
  // The value a channel (rig input or morph target name) has on screen now.
  virtual float currentValue(std::string_view channel) const = 0;
  virtual FaceSource source() const = 0;
  // A panel the user works in takes over the face.
  virtual void takeControl(FaceSource source) = 0;
};

// A panel's last message: shown in the panel and written to stderr, so a
// failed open or save is visible in the UI and in the log.
struct PanelMessage {
  std::string text;
  bool error = false;

  void report(std::string message, bool isError) {
    text = std::move(message);
    error = isError;
    std::fprintf(isError ? stderr : stdout, "facial-editor: %s%s\n", isError ? "error: " : "", text.c_str());
    std::fflush(isError ? stderr : stdout);
  }
  void draw() const;
};

}  // namespace editor
