// FBX files (binary and ASCII 7.x: node records, zlib arrays, meshes, blend
// shapes, skins, materials, embedded textures), read into a face as the face
// loader opens them.
#include "engine/scene/model_check.h"
#include "importers/load_face.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // In the scratch folder: a texture the input names is looked for beside it.
  auto face = importers::loadFaceFromBytes({data, size}, fuzz::scratchDir() / "face.fbx");
  if (face) {
    const auto consistent = eng::checkModel(face->model);
    FUZZ_PROPERTY(consistent.ok(), "FBX model fails checkModel: " + consistent.error().message);
  }
  return 0;
}
