#pragma once
// The channels a pose spans: the FACS action units of rig/action_units.h, or
// the raw morph target names of a mesh. Each channel may know its face region
// and side, which region masks (additive layers) select by.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/name_index.h"
#include "engine/core/result.h"
#include "facial/runtime/rig/action_units.h"

namespace facial {

struct ChannelInfo {
  std::string name;
  std::optional<FaceRegion> region;  // unknown for raw target names
  FaceSide side = FaceSide::Both;
};

class ChannelSet {
 public:
  ChannelSet() = default;
  // The action-unit channels, in actionUnits() order, with their regions and sides.
  static ChannelSet actionUnits();
  // actionUnits(), then the 15 viseme channels "viseme_sil" .. "viseme_U"
  // (lower face, both sides): the channels of a graph that speaks (speech
  // node; JSON "channels": "actionUnitsAndVisemes").
  static ChannelSet actionUnitsAndVisemes();
  // The first viseme channel when the set is actionUnitsAndVisemes()'s layout, else nullopt.
  std::optional<uint32_t> firstVisemeChannel() const;
  // Arbitrary names (e.g. a mesh's target names). Names that are action units
  // take the unit's region and side; others get their side from a suffix
  // (_L/_R, Left/Right) and no region. Fails on an empty or duplicate name.
  static eng::Result<ChannelSet> fromNames(std::span<const std::string> names);

  uint32_t size() const { return static_cast<uint32_t>(channels_.size()); }
  bool empty() const { return channels_.empty(); }
  const ChannelInfo& operator[](uint32_t i) const { return channels_[i]; }
  std::span<const ChannelInfo> channels() const { return channels_; }
  std::optional<uint32_t> find(std::string_view name) const;

 private:
  void add(ChannelInfo info);

  std::vector<ChannelInfo> channels_;
  eng::NameIndex index_;  // find() in one look-up: a mesh may have thousands of targets
};

}  // namespace facial
