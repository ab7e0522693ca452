#pragma once
// Minimal levelled logging. A sink can be installed so tests can capture
// (and fail on) messages, e.g. Vulkan validation output.
#include <functional>
#include <string>
#include <string_view>

namespace eng {

enum class LogLevel { Debug, Info, Warning, Error };

using LogSink = std::function<void(LogLevel, std::string_view)>;

// Replaces the sink; returns the previous one. The default writes to stderr
// (Info and above; Debug when FACIAL_LOG=debug).
LogSink setLogSink(LogSink sink);
void log(LogLevel level, std::string_view message);

inline void logDebug(std::string_view m) { log(LogLevel::Debug, m); }
inline void logInfo(std::string_view m) { log(LogLevel::Info, m); }
inline void logWarning(std::string_view m) { log(LogLevel::Warning, m); }
inline void logError(std::string_view m) { log(LogLevel::Error, m); }

}  // namespace eng
