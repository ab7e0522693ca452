#pragma once
// The names an enum's values have in files and on command lines, as one table
// read both ways. An enum with names declares its table once:
//
//   inline constexpr eng::EnumName<LoopMode> kLoopModeNames[] = {{LoopMode::Once, "once"}, ...};
//   std::string_view loopModeName(LoopMode m) { return eng::nameOf(kLoopModeNames, m); }
//   std::optional<LoopMode> loopModeFromName(std::string_view s) { return eng::valueNamed(kLoopModeNames, s); }
//
// so the name written and the name read can never drift apart, and messages
// list the accepted names from the same table (nameList).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace eng {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

// The value's name; "?" for a value the table does not list.
template <class E, size_t N>
constexpr std::string_view nameOf(const EnumName<E> (&names)[N], E value) {
  for (const EnumName<E>& n : names)
    if (n.value == value) return n.name;
  return "?";
}

// The value called `name` (exact match), or nullopt.
template <class E, size_t N>
constexpr std::optional<E> valueNamed(const EnumName<E> (&names)[N], std::string_view name) {
  for (const EnumName<E>& n : names)
    if (n.name == name) return n.value;
  return std::nullopt;
}

// "once, clamp, loop or pingpong": every name, for messages.
template <class E, size_t N>
std::string nameList(const EnumName<E> (&names)[N]) {
  std::string out;
  for (size_t i = 0; i < N; ++i) out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i].name);
  return out;
}

}  // namespace eng
