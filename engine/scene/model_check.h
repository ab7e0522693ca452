#pragma once
// Structural consistency of a Model built by hand or by an importer: every
// array has the length the others imply and every index points somewhere.
// The writer refuses models that fail it, so a file we write always loads.
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace eng {

// The first problem found, as one line naming the element and the sizes.
Result<void> checkModel(const Model& model);

}  // namespace eng
