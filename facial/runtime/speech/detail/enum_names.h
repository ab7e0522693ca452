#pragma once
// The names an enum's values have in files, as one table read both ways: the
// helpers of engine/core/enum_names.h on main, which this branch predates.
// In facial::detail so that the two never collide in one translation unit;
// when the branches meet, this file goes and viseme.cpp uses eng::EnumName.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace facial::detail {

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

// "a, b or c": every name, for messages.
template <class E, size_t N>
std::string nameList(const EnumName<E> (&names)[N]) {
  std::string out;
  for (size_t i = 0; i < N; ++i) out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(names[i].name);
  return out;
}

}  // namespace facial::detail
