#pragma once
// A text read line by line, for the text formats read by hand (an OBJ's
// statements, an MTL's maps, CANDIDE-3's sections): each line without its
// '\n' (a last line without one counts), trimmed of spaces, tabs and the
// '\r' of Windows line ends, numbered from 1 for "<file>:<line>:" messages.
#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

namespace eng {

// `s` without spaces, tabs and '\r' at either end.
inline std::string_view trimmed(std::string_view s) {
  const size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// At most `most` characters of `text` for a message, bytes outside printable
// ASCII as \xNN (a binary body read as text stays one line), "..." when cut.
inline std::string shownText(std::string_view text, size_t most = 40) {
  std::string out;
  for (char c : text.substr(0, most)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += {'\\', 'x', kHex[u >> 4], kHex[u & 15]};
    }
  }
  return text.size() > most ? out + "..." : out;
}

class TextLines {
 public:
  explicit TextLines(std::string_view text) : text_(text) {}

  // The next line that is not blank, trimmed; false at the end of the text.
  // A copy of the reader looks ahead without moving this one.
  bool nextNonBlank(std::string_view& line) {
    while (at_ < text_.size()) {
      const size_t end = std::min(text_.find('\n', at_), text_.size());
      line = trimmed(text_.substr(at_, end - at_));
      at_ = end + 1;
      ++number_;
      if (!line.empty()) return true;
    }
    line = {};
    return false;
  }
  // The number of the line last read (0 before the first).
  size_t number() const { return number_; }

 private:
  std::string_view text_;
  size_t at_ = 0;
  size_t number_ = 0;
};

}  // namespace eng
