#pragma once
// A graph-driven face's value for a channel name: a graph channel (action
// unit) when the graph has it, else a morph target of the model.
#include <span>
#include <string>
#include <string_view>

#include "facial/runtime/character/face_driver.h"

namespace editor {

float driverChannelValue(const facial::FaceDriver& driver, std::span<const std::string> targetNames, std::string_view channel);

}  // namespace editor
