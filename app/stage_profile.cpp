#include "app/stage_profile.h"

#include <algorithm>
#include <cstdio>

namespace app {

StageProfile::StageProfile(std::vector<std::string> stages) {
  for (std::string& name : stages) stages_.push_back({std::move(name)});
}

void StageProfile::add(size_t stage, double ms) {
  if (stage >= stages_.size()) return;
  stages_[stage].totalMs += ms;
  ++stages_[stage].samples;
}

std::string StageProfile::format(const std::string& title, double wallSeconds) const {
  const double frameMs = frames_ > 0 ? 1000.0 * wallSeconds / frames_ : 0.0;
  char line[160];
  std::snprintf(line, sizeof line, "profile %s: %u frames, %.2f ms a frame (mean ms per frame, share of it)\n",
                title.c_str(), frames_, frameMs);
  std::string text = line;
  size_t width = 0;
  for (const Stage& s : stages_) width = std::max(width, s.name.size());
  for (const Stage& s : stages_) {
    if (s.samples == 0) continue;  // not measured (no PNGs, no timestamps)
    // Per frame, so a stage some frames skip still weighs what it cost.
    const double mean = frames_ > 0 ? s.totalMs / frames_ : 0.0;
    std::snprintf(line, sizeof line, "  %-*s %9.3f ms %6.1f %%\n", int(width), s.name.c_str(), mean,
                  frameMs > 0.0 ? 100.0 * mean / frameMs : 0.0);
    text += line;
  }
  return text;
}

void StageProfile::print(const std::string& title, double wallSeconds) const {
  std::fputs(format(title, wallSeconds).c_str(), stdout);
}

}  // namespace app
