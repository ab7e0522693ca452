#include "engine/core/log.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace eng {
namespace {

std::mutex& sinkMutex() {
  static std::mutex m;
  return m;
}

void defaultSink(LogLevel level, std::string_view message) {
  static const bool debug = [] {
    const char* v = std::getenv("FACIAL_LOG");
    return v && std::strcmp(v, "debug") == 0;
  }();
  if (level == LogLevel::Debug && !debug) return;
  static const char* const kPrefix[] = {"debug", "info", "warning", "error"};
  std::fprintf(stderr, "[%s] %.*s\n", kPrefix[static_cast<int>(level)], static_cast<int>(message.size()),
               message.data());
}

LogSink& sink() {
  static LogSink s = defaultSink;
  return s;
}

}  // namespace

LogSink setLogSink(LogSink newSink) {
  std::lock_guard lock(sinkMutex());
  LogSink old = std::move(sink());
  sink() = newSink ? std::move(newSink) : LogSink(defaultSink);
  return old;
}

void log(LogLevel level, std::string_view message) {
  LogSink s;
  {
    std::lock_guard lock(sinkMutex());
    s = sink();
  }
  s(level, message);
}

}  // namespace eng
