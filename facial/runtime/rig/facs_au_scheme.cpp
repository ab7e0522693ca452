// ActionUnits scheme: targets named exactly like the channels
// ("AU12_LipCornerPuller_L") or by FACS number ("AU12", "AU12_L", "au04_right",
// "AU6 Cheek raiser").
#include <charconv>
#include <optional>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

struct FacsTarget {
  int number = 0;
  FaceSide side = FaceSide::Both;
};

bool endsWith(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

bool knownFacsNumber(int number) {
  for (const ActionUnitInfo& au : actionUnits())
    if (au.facsNumber == number) return true;
  return false;
}

// "AU12_L" -> {12, Left}; nullopt for names that are not FACS-numbered or
// whose number is not in the channel vocabulary.
std::optional<FacsTarget> parseFacsName(std::string_view name) {
  if (std::optional<uint32_t> channel = actionUnitIndex(name)) {
    const ActionUnitInfo& au = actionUnits()[*channel];
    return FacsTarget{au.facsNumber, au.side};
  }
  const std::string lower = asciiLower(name);
  if (lower.size() < 3 || lower.compare(0, 2, "au") != 0) return std::nullopt;
  size_t pos = 2;
  if (lower[pos] == '_' || lower[pos] == ' ') ++pos;
  int number = 0;
  const auto [end, ec] = std::from_chars(lower.data() + pos, lower.data() + lower.size(), number);
  if (ec != std::errc() || end == lower.data() + pos || !knownFacsNumber(number)) return std::nullopt;
  const std::string_view rest(end, static_cast<size_t>(lower.data() + lower.size() - end));
  FacsTarget target{number, FaceSide::Both};
  if (endsWith(rest, "_l") || endsWith(rest, "left") || endsWith(rest, ".l")) target.side = FaceSide::Left;
  if (endsWith(rest, "_r") || endsWith(rest, "right") || endsWith(rest, ".r")) target.side = FaceSide::Right;
  return target;
}

}  // namespace

SchemeRecognition recogniseActionUnitNames(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  for (const std::string& name : targetNames) r.recognised += parseFacsName(name) ? 1 : 0;
  r.detail = std::to_string(r.recognised) + " of " + std::to_string(targetNames.size()) +
             " target names are FACS action units";
  return r;
}

void mapActionUnitNames(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  const std::span<const ActionUnitInfo> channels = actionUnits();
  for (uint32_t t = 0; t < names.size(); ++t) {
    const std::optional<FacsTarget> target = parseFacsName(names[t]);
    if (!target) continue;
    // Channels of the same FACS number: a one-sided target takes its side's
    // channel (and a bilateral channel); a bilateral target takes the mean of a
    // split channel's two sides so a symmetric pose reaches 1.
    for (uint32_t c = 0; c < channels.size(); ++c) {
      const ActionUnitInfo& au = channels[c];
      if (au.facsNumber != target->number) continue;
      if (target->side == FaceSide::Both) builder.add(c, t, au.side == FaceSide::Both ? 1.0f : 0.5f);
      else if (au.side == FaceSide::Both || au.side == target->side) builder.add(c, t, 1.0f);
    }
  }
}

}  // namespace facial
