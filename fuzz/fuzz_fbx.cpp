// FBX files (binary and ASCII 7.x: node records, zlib arrays, meshes, blend
// shapes, skins, materials, embedded textures, animations), read into a face
// as the face loader opens them.
#include "fuzz/face_file_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return fuzz::loadFaceFile(data, size, "face.fbx"); }
