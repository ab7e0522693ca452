#pragma once
// How the `facial` program's commands and the editor report a failure: one
// line on stderr, "<program>: error: <message>", and exit code 1. Each file
// names its program once and keeps calling `fail(message)`:
//
//   constexpr app::ErrorReporter fail{"facial render"};
//   if (!setup) return fail(setup.error().message);
#include <string_view>

namespace app {

struct ErrorReporter {
  std::string_view program;  // "facial render", "facial-editor"
  // Prints "<program>: error: <message>" and returns 1, the exit code.
  int operator()(std::string_view message) const;
};

}  // namespace app
