#pragma once
// The canonical FACS channel vocabulary shared by presets, the animation graph
// and rig mappings. A pose over action units is a float per entry of
// actionUnits(), in this order. Bilateral units are split where one-sided
// motion is common (2, 12, 45); the others act on both sides. 19 is FACS's
// action descriptor "tongue show" (the tongue tip up between the teeth, as for
// th, t, d, n, l): a tongue channel in the same vocabulary, so FACS-named faces
// ("AU19") and ARKit's tongueOut both reach it.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace facial {

enum class FaceRegion : uint8_t { Upper, Lower };
enum class FaceSide : uint8_t { Both, Left, Right };

struct ActionUnitInfo {
  std::string_view name;     // channel name, e.g. "AU12_LipCornerPuller_L"
  int facsNumber;            // 12
  std::string_view facsName; // "Lip Corner Puller"
  FaceRegion region;
  FaceSide side;
};

// All channels, in channel order.
std::span<const ActionUnitInfo> actionUnits();
// Channel index of a name ("AU12_LipCornerPuller_L"), or nullopt.
std::optional<uint32_t> actionUnitIndex(std::string_view name);

}  // namespace facial
