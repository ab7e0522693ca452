#pragma once
// Sample-rate conversion of mono float audio (libswresample), shared by the
// video writer (AAC and Opus rates) and the aligner (16 kHz models).
#include <span>
#include <vector>

#include "engine/core/result.h"

namespace audio {

// `samples` at fromRate as the same sound at toRate (both 1000..384000 Hz).
eng::Result<std::vector<float>> resampleMono(std::span<const float> samples, int fromRate, int toRate);

}  // namespace audio
