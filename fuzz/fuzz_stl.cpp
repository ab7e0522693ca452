// STL scans (binary, whatever the header says, or ASCII), read into a face
// without targets, as the face loader opens them.
#include "engine/scene/model_check.h"
#include "importers/load_face.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto face = importers::loadFaceFromBytes({data, size}, fuzz::scratchDir() / "scan.stl");
  if (face) {
    const auto consistent = eng::checkModel(face->model);
    FUZZ_PROPERTY(consistent.ok(), "STL model fails checkModel: " + consistent.error().message);
  }
  return 0;
}
