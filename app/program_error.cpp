#include "app/program_error.h"

#include <algorithm>
#include <cstdio>

namespace app {

namespace {

bool isContinuationByte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }
bool isBlank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

std::string elideMiddle(std::string_view text, size_t limit) {
  if (text.size() <= limit) return std::string(text);
  const std::string marker = "...(" + std::to_string(text.size()) + " bytes)...";
  const size_t keep = limit > marker.size() ? limit - marker.size() : 0;
  size_t head = keep / 2, tail = text.size() - (keep - keep / 2);
  while (head > 0 && isContinuationByte(text[head])) --head;
  while (tail < text.size() && isContinuationByte(text[tail])) ++tail;
  return std::string(text.substr(0, head)) + marker + std::string(text.substr(tail));
}

std::string shortenNames(std::string_view message) {
  std::string out;
  size_t i = 0;
  while (i < message.size()) {
    size_t end = i;
    const bool blank = isBlank(message[i]);
    while (end < message.size() && isBlank(message[end]) == blank) ++end;
    const std::string_view run = message.substr(i, end - i);
    out += blank ? std::string(run) : elideMiddle(run, kMaxNameInMessage);
    i = end;
  }
  return elideMiddle(out, kMaxMessageLine);
}

std::string shortenEachLine(std::string_view text) {
  std::string out;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    out += shortenNames(text.substr(start, end - start)) + "\n";
    start = end + 1;
  }
  return out;
}

void printWarning(std::string_view program, std::string_view message) {
  const std::string line = shortenNames(message);
  std::fprintf(stderr, "%.*s: warning: %s\n", static_cast<int>(program.size()), program.data(), line.c_str());
}

int ErrorReporter::operator()(std::string_view message) const {
  const std::string line = shortenNames(message);
  std::fprintf(stderr, "%.*s: error: %s\n", static_cast<int>(program.size()), program.data(), line.c_str());
  return 1;
}

}  // namespace app
