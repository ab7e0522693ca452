#pragma once
// One budget per load. Every allocation whose size a file's numbers decide
// (counts, byteLengths, image sizes, JSON entries, subdivision levels, key
// rates) is charged here before it is made, so a small hostile file fails
// with one line naming what it was making and the limit, instead of taking
// gigabytes (or ending in a bare std::bad_alloc). Loaders take the limit from
// their options (GltfLoadLimits::maxDecodedBytes and friends); the defaults
// sit far above what a real avatar costs (docs/reliability.md).
#include <cstddef>
#include <string_view>

#include "engine/core/result.h"

namespace eng {

inline constexpr size_t kDefaultLoadBudgetBytes = size_t{1} << 30;

class LoadBudget {
 public:
  explicit LoadBudget(size_t limitBytes = kDefaultLoadBudgetBytes) : limit_(limitBytes) {}

  // Charges `count` items of `bytesEach` bytes made for `what` ("material 12",
  // "mesh 0 primitive 1 target 3"). Past the limit nothing is charged and the
  // TooLarge error says what, how many bytes and the limit; the caller puts
  // the file in front. Overflow-safe for any count.
  Result<void> charge(size_t count, size_t bytesEach, std::string_view what);
  Result<void> charge(size_t bytes, std::string_view what) { return charge(1, bytes, what); }

  size_t charged() const { return charged_; }
  size_t limit() const { return limit_; }
  size_t left() const { return limit_ - charged_; }

 private:
  size_t limit_;
  size_t charged_ = 0;
};

}  // namespace eng
