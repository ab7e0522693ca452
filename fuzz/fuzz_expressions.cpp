// Expression presets (data/expressions.json format) and, for a library that
// loads, every preset evaluated at intensities inside and outside [0, 1]:
// the weights must stay finite and in [0, 1].
#include <cmath>
#include <string_view>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/expression_library.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto library = facial::ExpressionLibrary::parse(text, "expressions.json");
  if (!library) return 0;
  std::vector<float> au(facial::actionUnits().size());
  for (const facial::ExpressionPreset& preset : library->presets()) {
    for (float intensity : {0.0f, 0.5f, 1.0f, 7.0f, -3.0f}) {
      if (!facial::ExpressionLibrary::evaluate(preset, intensity, au)) continue;
      for (float w : au) FUZZ_PROPERTY(std::isfinite(w) && w >= 0.0f && w <= 1.0f, "preset " + preset.name);
    }
  }
  return 0;
}
