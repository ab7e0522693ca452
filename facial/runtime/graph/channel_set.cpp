#include "facial/runtime/graph/channel_set.h"

#include "facial/runtime/rig/rig_mapping.h"  // rigVisemeInputName

namespace facial {
namespace {

bool endsWith(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

FaceSide sideFromSuffix(std::string_view name) {
  if (endsWith(name, "_L") || endsWith(name, "Left") || endsWith(name, "_left")) return FaceSide::Left;
  if (endsWith(name, "_R") || endsWith(name, "Right") || endsWith(name, "_right")) return FaceSide::Right;
  return FaceSide::Both;
}

}  // namespace

ChannelSet ChannelSet::actionUnits() {
  ChannelSet set;
  for (const ActionUnitInfo& au : facial::actionUnits())
    set.add({std::string(au.name), au.region, au.side});
  return set;
}

ChannelSet ChannelSet::actionUnitsAndVisemes() {
  ChannelSet set = actionUnits();
  for (size_t v = 0; v < kVisemeCount; ++v) set.add({rigVisemeInputName(Viseme(v)), FaceRegion::Lower, FaceSide::Both});
  return set;
}

std::optional<uint32_t> ChannelSet::firstVisemeChannel() const {
  const std::span<const ActionUnitInfo> units = facial::actionUnits();
  if (channels_.size() != units.size() + kVisemeCount) return std::nullopt;
  for (size_t c = 0; c < units.size(); ++c)
    if (channels_[c].name != units[c].name) return std::nullopt;
  for (size_t v = 0; v < kVisemeCount; ++v)
    if (channels_[units.size() + v].name != rigVisemeInputName(Viseme(v))) return std::nullopt;
  return static_cast<uint32_t>(units.size());
}

eng::Result<ChannelSet> ChannelSet::fromNames(std::span<const std::string> names) {
  ChannelSet set;
  set.channels_.reserve(names.size());
  set.index_.reserve(names.size());
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    if (name.empty()) return eng::makeError(eng::ErrorKind::Malformed, "channel " + std::to_string(i) + " has an empty name");
    if (set.find(name)) return eng::makeError(eng::ErrorKind::Malformed, "channel name '" + name + "' appears twice");
    if (auto au = actionUnitIndex(name)) {
      const ActionUnitInfo& info = facial::actionUnits()[*au];
      set.add({name, info.region, info.side});
    } else {
      set.add({name, std::nullopt, sideFromSuffix(name)});
    }
  }
  return set;
}

void ChannelSet::add(ChannelInfo info) {
  index_.add(info.name, static_cast<uint32_t>(channels_.size()));
  channels_.push_back(std::move(info));
}

std::optional<uint32_t> ChannelSet::find(std::string_view name) const { return index_.find(name); }

}  // namespace facial
