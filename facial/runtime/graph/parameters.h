#pragma once
// Named graph parameters. The definition declares them; each instance keeps
// their values in one flat float block (bool and trigger as 0/1), addressed
// by index so the per-frame path never looks up a name.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "engine/core/enum_names.h"

namespace facial {

using ParameterIndex = uint32_t;
inline constexpr ParameterIndex kNoParameter = std::numeric_limits<ParameterIndex>::max();

enum class ParameterType : uint8_t {
  Float,
  Bool,
  Trigger,  // set by the application, cleared when a transition consumes it
};

inline constexpr eng::EnumName<ParameterType> kParameterTypeNames[] = {
    {ParameterType::Float, "float"},
    {ParameterType::Bool, "bool"},
    {ParameterType::Trigger, "trigger"},
};
std::string_view parameterTypeName(ParameterType value);
std::optional<ParameterType> parameterTypeFromName(std::string_view name);

struct ParameterDecl {
  std::string name;
  ParameterType type = ParameterType::Float;
  float defaultValue = 0;  // 0/1 for Bool; triggers start cleared
};

// A float that is either a constant or a parameter's current value.
struct FloatInput {
  ParameterIndex parameter = kNoParameter;
  float constant = 0;

  static FloatInput fixed(float value) { return {kNoParameter, value}; }
  static FloatInput bound(ParameterIndex p) { return {p, 0}; }
  float read(std::span<const float> values) const { return parameter == kNoParameter ? constant : values[parameter]; }
};

}  // namespace facial
