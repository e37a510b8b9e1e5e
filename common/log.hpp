// Minimal leveled logging to stderr, tagged with the component. Level from A3_LOG_LEVEL
// (debug|info|warn|error, default info) or set_log_level(). Thread-safe, line-atomic.
#pragma once

#include <string>
#include <string_view>

namespace a3::common {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3, kOff = 4 };

void set_log_level(LogLevel level);
LogLevel log_level();
// Parses "debug|info|warn|error|off"; throws std::invalid_argument naming the bad value.
LogLevel parse_log_level(std::string_view text);
void log(LogLevel level, std::string_view component, std::string_view message);

inline void log_debug(std::string_view c, std::string_view m) { log(LogLevel::kDebug, c, m); }
inline void log_info(std::string_view c, std::string_view m) { log(LogLevel::kInfo, c, m); }
inline void log_warn(std::string_view c, std::string_view m) { log(LogLevel::kWarn, c, m); }
inline void log_error(std::string_view c, std::string_view m) { log(LogLevel::kError, c, m); }

}  // namespace a3::common
