// Animation graph files (data/graphs/*.json) with the project's expression
// presets. A graph that loads is instantiated and run: 200 updates with
// varied time steps, every trigger fired, float parameters swept through
// ordinary and extreme values. Every weight must stay finite.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "facial/runtime/graph/graph_instance.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/rig/expression_library.h"
#include "fuzz/fuzz_support.h"
#include "fuzz/json_growth.h"

namespace {

// The project's presets, loaded once.
const facial::ExpressionLibrary& library() {
  static const facial::ExpressionLibrary loaded = [] {
    auto library = facial::ExpressionLibrary::load(fuzz::sourceDir() / "data" / "expressions.json");
    if (!library) {
      std::fprintf(stderr, "fuzz_graph: %s\n", library.error().message.c_str());
      std::abort();
    }
    return std::move(library).value();
  }();
  return loaded;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = fuzz::writeInput("graph.json", data, size);
  auto graph = facial::loadGraph(path, {facial::presetLookup(library())});
  if (!graph) return 0;
  auto instance = facial::GraphInstance::create(*graph, /*seed=*/size);
  if (!instance) return 0;
  const auto parameters = (*graph)->parameters();
  constexpr float kSweep[] = {0.0f, 1.0f, 0.5f, -1.0f, 1e6f, -1e-7f};
  constexpr float kSteps[] = {1.0f / 60, 0.0f, 0.25f, 1.0f / 240, 3.0f};
  for (int frame = 0; frame < 200; ++frame) {
    for (facial::ParameterIndex p = 0; p < parameters.size(); ++p) {
      switch (parameters[p].type) {
        case facial::ParameterType::Trigger:
          if ((frame + p) % 17 == 0) instance->setTrigger(p);
          break;
        case facial::ParameterType::Bool:
          instance->setBool(p, ((frame / 13 + p) & 1) != 0);
          break;
        case facial::ParameterType::Float:
          if (frame % 11 == 0) instance->setFloat(p, kSweep[(frame / 11 + p) % std::size(kSweep)]);
          break;
      }
    }
    instance->update(kSteps[frame % std::size(kSteps)]);
    for (float w : instance->weights())
      FUZZ_PROPERTY(std::isfinite(w), "frame " + std::to_string(frame) + ": weight " + std::to_string(w));
  }
  return 0;
}

// Larger graphs and timelines than byte mutations make (fuzz/json_growth.h).
FUZZ_GROW_JSON_MUTATOR
