#pragma once
// One dataset item's parameters, drawn from the spec's seed and the item's
// index alone (a counter-based generator: splitmix64 of seed and index), so
// any shard, in any order, on any machine, makes the same item k.
#include <cstdint>
#include <vector>

#include "dataset/dataset_spec.h"
#include "facial/runtime/rig/expression_library.h"

namespace dataset {

struct ItemParams {
  uint64_t index = 0;
  uint32_t model = 0;       // into spec.models
  uint32_t emotion = 0;     // into spec.emotions
  float intensity = 1.0f;
  // Random action units laid over the emotion (spec.auMix), ascending channel order.
  std::vector<facial::ActionUnitWeight> extraUnits;
  float yaw = 0.0f, pitch = 0.0f, zoom = 1.0f;
  uint32_t light = 0;       // into spec.lights
  uint32_t background = 0;  // into spec.backgrounds
};

ItemParams sampleItem(const DatasetSpec& spec, uint64_t index);

// The preset rendered for an item: the emotion's action units, each raised to
// the item's random units where those are stronger (intensity applies to the
// emotion's units only; the random ones carry their own weight).
facial::ExpressionPreset itemPreset(const facial::ExpressionPreset& emotion, const ItemParams& item);

}  // namespace dataset
