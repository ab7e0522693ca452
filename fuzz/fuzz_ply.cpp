// PLY scans (ASCII or binary; vertex colours, texture coordinates, MeshLab's
// texture comment), read into a face without targets, as the face loader
// opens them.
#include "fuzz/face_file_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return fuzz::loadFaceFile(data, size, "scan.ply"); }
