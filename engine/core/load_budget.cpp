#include "engine/core/load_budget.h"

#include <limits>
#include <string>

namespace eng {

Result<void> LoadBudget::charge(size_t count, size_t bytesEach, std::string_view what) {
  const bool overflows = bytesEach != 0 && count > std::numeric_limits<size_t>::max() / bytesEach;
  const size_t bytes = overflows ? std::numeric_limits<size_t>::max() : count * bytesEach;
  if (bytes > left()) {
    const std::string needed = overflows ? std::to_string(count) + " x " + std::to_string(bytesEach) : std::to_string(bytes);
    return makeError(ErrorKind::TooLarge, std::string(what) + " would take " + needed + " bytes, past the load budget of " +
                                              std::to_string(limit_) + " bytes (" + std::to_string(charged_) +
                                              " already charged)");
  }
  charged_ += bytes;
  return {};
}

}  // namespace eng
