#include "editor/app/driver_channels.h"

#include <algorithm>

namespace editor {

float driverChannelValue(const facial::FaceDriver& driver, std::span<const std::string> targetNames, std::string_view channel) {
  if (const auto index = driver.graph().definition().channels().find(channel)) return driver.channelWeights()[*index];
  const auto it = std::find(targetNames.begin(), targetNames.end(), channel);
  if (it != targetNames.end()) return driver.targetWeights()[size_t(it - targetNames.begin())];
  return 0.0f;
}

}  // namespace editor
