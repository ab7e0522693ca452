#include "app/progress_bar.h"

#include <algorithm>
#include <unistd.h>

namespace app {

ProgressBar::ProgressBar(std::string label, size_t total, std::FILE* out)
    : label_(std::move(label)),
      total_(std::max<size_t>(total, 1)),
      out_(out),
      interactive_(isatty(fileno(out)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(size_t done) {
  done = std::min(done, total_);
  const double fraction = static_cast<double>(done) / static_cast<double>(total_);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done > 0 ? elapsed / fraction - elapsed : 0.0;
  if (interactive_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(out_, "\r%s [%s%s] %3d%% %zu/%zu  %.1fs elapsed, ~%.0fs left ", label_.c_str(),
                 std::string(static_cast<size_t>(filled), '#').c_str(),
                 std::string(static_cast<size_t>(kWidth - filled), '.').c_str(), static_cast<int>(fraction * 100),
                 done, total_, elapsed, eta);
    std::fflush(out_);
    return;
  }
  const int decile = static_cast<int>(fraction * 10);
  if (decile != lastDecile_) {
    lastDecile_ = decile;
    std::fprintf(out_, "%s: %3d%% (%zu/%zu, %.1fs)\n", label_.c_str(), decile * 10, done, total_, elapsed);
    std::fflush(out_);
  }
}

void ProgressBar::finish() {
  update(total_);
  if (interactive_) std::fprintf(out_, "\n");
}

}  // namespace app
