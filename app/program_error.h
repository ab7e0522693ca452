#pragma once
// How the `facial` program's commands and the editor report a failure: one
// line on stderr, "<program>: error: <message>", and exit code 1. Each file
// names its program once and keeps calling `fail(message)`:
//
//   constexpr app::ErrorReporter fail{"facial render"};
//   if (!setup) return fail(setup.error().message);
#include <cstddef>
#include <string>
#include <string_view>

namespace app {

// Longer names are shortened in messages: a path this long is already rare.
inline constexpr size_t kMaxNameInMessage = 240;
// And a whole line past this (many long words) is shortened as one.
inline constexpr size_t kMaxMessageLine = 2000;

// `text` when it fits in `limit` bytes, else its start and end around
// "...(N bytes)...", cut between UTF-8 characters.
std::string elideMiddle(std::string_view text, size_t limit);
// `message` with each word (run of non-blanks: a file name, a quoted value)
// longer than kMaxNameInMessage elided in the middle, then the line to kMaxMessageLine.
std::string shortenNames(std::string_view message);
// Each line of a multi-line text (CLI11's usage errors) shortened so; every line ends in '\n'.
std::string shortenEachLine(std::string_view text);

// Prints "<program>: warning: <message>" on stderr, names shortened: a
// warning quotes names from the file (nodes, targets, images) as errors do.
void printWarning(std::string_view program, std::string_view message);

struct ErrorReporter {
  std::string_view program;  // "facial render", "facial-editor"
  // Prints "<program>: error: <message>" (names shortened) and returns 1, the exit code.
  int operator()(std::string_view message) const;
};

}  // namespace app
