#pragma once
// A one-line terminal progress bar for long headless runs (frames rendered,
// tour steps). Redraws in place on a terminal; prints every 10% otherwise so
// CI logs stay short.
#include <chrono>
#include <cstdio>
#include <string>

namespace app {

class ProgressBar {
 public:
  ProgressBar(std::string label, size_t total, std::FILE* out = stderr);
  void update(size_t done);
  void finish();

 private:
  std::string label_;
  size_t total_;
  std::FILE* out_;
  bool interactive_;
  int lastDecile_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace app
