#pragma once
// The body of the fuzzers that read one face file through the face loader
// (PLY, STL, FBX): the input is the file's bytes, named `name` in the scratch
// folder (a texture it names is looked for beside it); what loads must pass
// checkModel.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/scene/model_check.h"
#include "importers/load_face.h"
#include "fuzz/fuzz_support.h"

namespace fuzz {

inline int loadFaceFile(const uint8_t* data, size_t size, const char* name) {
  auto face = importers::loadFaceFromBytes({data, size}, scratchDir() / name);
  if (face) {
    const auto consistent = eng::checkModel(face->model);
    FUZZ_PROPERTY(consistent.ok(), std::string(name) + ": the model fails checkModel: " + consistent.error().message);
  }
  return 0;
}

}  // namespace fuzz
