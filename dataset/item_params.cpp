#include "dataset/item_params.h"

#include <algorithm>

#include "facial/runtime/rig/action_units.h"

namespace dataset {
namespace {

// Counter-based: every draw is a hash of (seed, index, draw number), so an
// item's values never depend on another item's.
class ItemRandom {
 public:
  ItemRandom(uint64_t seed, uint64_t index) : state_(mix(seed ^ mix(index + 0x632be59bd9b4e019ull))) {}

  uint64_t next() { return mix(state_ += 0x9e3779b97f4a7c15ull); }
  // [0, 1) with 24 bits: exact in float, the same on every machine.
  float unit() { return float(next() >> 40) * (1.0f / 16777216.0f); }
  float in(Range r) { return r.min + (r.max - r.min) * unit(); }
  uint32_t below(uint64_t n) { return n <= 1 ? 0u : uint32_t(next() % n); }

 private:
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  uint64_t state_;
};

std::vector<facial::ActionUnitWeight> randomUnits(const AuMix& mix, ItemRandom& random) {
  std::vector<facial::ActionUnitWeight> units;
  const bool mixed = random.unit() < mix.probability;
  const uint32_t count = mix.minUnits + random.below(uint64_t(mix.maxUnits - mix.minUnits) + 1);
  const uint32_t channels = uint32_t(facial::actionUnits().size());
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t channel = random.below(channels);
    const float weight = random.in(mix.weight);
    if (!mixed || std::any_of(units.begin(), units.end(), [&](const auto& u) { return u.channel == channel; })) continue;
    units.push_back({channel, weight});
  }
  std::sort(units.begin(), units.end(), [](const auto& a, const auto& b) { return a.channel < b.channel; });
  return units;
}

}  // namespace

ItemParams sampleItem(const DatasetSpec& spec, uint64_t index) {
  ItemRandom random(spec.seed, index);
  ItemParams item;
  item.index = index;
  // A fixed number of draws in a fixed order: a spec change in one field
  // leaves the other fields' draws where they were.
  item.model = random.below(spec.models.size());
  item.emotion = random.below(spec.emotions.size());
  item.intensity = random.in(spec.intensity);
  item.yaw = random.in(spec.yaw);
  item.pitch = random.in(spec.pitch);
  item.zoom = random.in(spec.zoom);
  item.light = random.below(spec.lights.size());
  item.background = random.below(spec.backgrounds.size());
  item.extraUnits = randomUnits(spec.auMix, random);
  return item;
}

facial::ExpressionPreset itemPreset(const facial::ExpressionPreset& emotion, const ItemParams& item) {
  facial::ExpressionPreset preset = emotion;
  for (facial::ActionUnitWeight& unit : preset.actionUnits) unit.weight *= item.intensity;
  for (const facial::ActionUnitWeight& extra : item.extraUnits) {
    auto at = std::find_if(preset.actionUnits.begin(), preset.actionUnits.end(),
                           [&](const auto& u) { return u.channel == extra.channel; });
    if (at == preset.actionUnits.end()) preset.actionUnits.push_back(extra);
    else at->weight = std::max(at->weight, extra.weight);
  }
  std::sort(preset.actionUnits.begin(), preset.actionUnits.end(), [](const auto& a, const auto& b) { return a.channel < b.channel; });
  for (float& e : preset.emotions) e *= item.intensity;
  return preset;
}

}  // namespace dataset
