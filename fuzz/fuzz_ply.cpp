// PLY scans (ASCII or binary; vertex colours, texture coordinates, MeshLab's
// texture comment), read into a face without targets, as the face loader
// opens them.
#include "engine/scene/model_check.h"
#include "importers/load_face.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // In the scratch folder: a texture the input names is looked for beside it.
  auto face = importers::loadFaceFromBytes({data, size}, fuzz::scratchDir() / "scan.ply");
  if (face) {
    const auto consistent = eng::checkModel(face->model);
    FUZZ_PROPERTY(consistent.ok(), "PLY model fails checkModel: " + consistent.error().message);
  }
  return 0;
}
