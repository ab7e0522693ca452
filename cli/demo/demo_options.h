#pragma once
// Options of `facial demo`, shared by its windowed and headless paths.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace cli {

// The seven triggers of the tour graph (data/graphs/tour.json), in the window's key order (1-7).
inline constexpr std::array<const char*, 7> kEmotions = {"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"};

struct DemoOptions {
  std::string model;               // empty: the built-in head
  std::string rigmap;              // empty: <data>/rigmaps/<model>.json or the detected scheme
  bool noAutorig = false;          // refuse a face that cannot show emotions (FaceSetupOptions::autorig)
  std::vector<std::string> shapes; // --shape NAME=VALUE identity parameters (CANDIDE-3 shape units)
  std::string graph;               // empty: data/graphs/tour.json
  std::string clip;                // skeletal clip of the model under the face (name, index, "all"); empty: none
  bool headless = false;           // forced headless even with a display
  std::string out;                 // headless output folder (empty: out/demo-<time>)
  std::string size = "";           // WxH; default 384x384 headless, 1280x800 windowed
  float fps = 10.0f;               // headless frame rate
  float seconds = 0.0f;            // headless length (0: one tour, all seven states and back)
  std::string frame = "face";      // face (head and neck) | all (the whole model); windowed: F toggles
  uint32_t crowd = 0;              // >0: N faces in a grid, each with its own state machine
  uint64_t seed = 1;
  std::string device;              // Vulkan device (eng::vk::ContextOptions::device); empty: FACIAL_DEVICE or the best
  std::string quality = "auto";    // auto | fast | balanced | high (app::windowQualityOption; headless: auto = high)
  bool profile = false;            // print where the frames' time went (windowed: on exit)
  float quitAfter = 0.0f;          // windowed: close after this many seconds (tests), 0 = never
  std::string screenshot;          // windowed: last frame's screenshot file (F12 shots go beside it)
  std::string script;              // windowed: timed actions (window_script.h)
  bool still = false;              // windowed: no idle sway, breathing or saccades (comparable shots)
  bool mute = false;               // windowed: the Speak button's voice is not played (the mouth still moves)
};

int runHeadlessDemo(const DemoOptions& options);
int runWindowDemo(const DemoOptions& options);

}  // namespace cli
