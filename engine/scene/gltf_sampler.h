#pragma once
// glTF samplers: the WebGL enum codes a file stores <-> eng::TextureSampling.
#include <string>

#include "engine/scene/model.h"

namespace eng {

struct GltfSamplerCodes {
  int magFilter = -1;  // -1: not given (the reader chooses)
  int minFilter = -1;
  int wrapS = 10497;   // REPEAT
  int wrapT = 10497;
};

// The sampling a glTF sampler asks for. A code glTF does not define is named
// in `problem` and leaves that setting at its default.
TextureSampling samplingFromGltf(const GltfSamplerCodes& codes, std::string& problem);

// The codes that ask for `sampling`, for writing it back.
GltfSamplerCodes gltfCodesOf(const TextureSampling& sampling);

}  // namespace eng
