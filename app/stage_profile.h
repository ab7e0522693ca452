#pragma once
// --profile: where a loop's time goes, one line per stage with its mean ms
// per frame and its share of the frame's wall time, printed at the end.
// Stages on the device (GPU timestamps) overlap the CPU's, so shares need
// not add up to 100 %.
//
//   app::StageProfile profile({"step", "submit", "encode"});
//   per frame: profile.add(0, ms); ...; profile.endFrame();
//   profile.print("play", wallSeconds);
#include <cstdint>
#include <string>
#include <vector>

namespace app {

class StageProfile {
 public:
  explicit StageProfile(std::vector<std::string> stages);

  void add(size_t stage, double ms);
  void endFrame() { ++frames_; }
  uint32_t frames() const { return frames_; }
  // The lines, e.g. "profile play: 120 frames, 41.2 ms a frame" then
  // "  wait for the GPU   35.10 ms  85.2 %" per stage that was measured.
  std::string format(const std::string& title, double wallSeconds) const;
  void print(const std::string& title, double wallSeconds) const;

 private:
  struct Stage {
    std::string name;
    double totalMs = 0.0;
    uint32_t samples = 0;
  };
  std::vector<Stage> stages_;
  uint32_t frames_ = 0;
};

}  // namespace app
