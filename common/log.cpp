// Leveled logging to stderr.
#include "common/log.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

namespace a3::common {
namespace {

LogLevel level_from_env() {
  const char* env = std::getenv("A3_LOG_LEVEL");
  if (env == nullptr || *env == '\0') return LogLevel::kInfo;
  try {
    return parse_log_level(env);
  } catch (const std::invalid_argument&) {
    return LogLevel::kInfo;
  }
}

std::atomic<LogLevel>& level_storage() {
  static std::atomic<LogLevel> level{level_from_env()};
  return level;
}

std::mutex& output_mutex() {
  static std::mutex m;
  return m;
}

// The message as the terminal should show it: a control character (ESC, which would start a
// terminal escape sequence, a carriage return that would overwrite the line, ...) as \xHH.
// Messages carry text from models and files, which must not drive the user's terminal.
std::string terminal_safe(std::string_view message) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

void set_log_level(LogLevel level) { level_storage().store(level); }
LogLevel log_level() { return level_storage().load(); }

LogLevel parse_log_level(std::string_view text) {
  if (text == "debug") return LogLevel::kDebug;
  if (text == "info") return LogLevel::kInfo;
  if (text == "warn") return LogLevel::kWarn;
  if (text == "error") return LogLevel::kError;
  if (text == "off") return LogLevel::kOff;
  throw std::invalid_argument("unknown log level '" + std::string(text) +
                              "' (expected debug, info, warn, error or off)");
}

void log(LogLevel level, std::string_view component, std::string_view message) {
  if (level < log_level() || level == LogLevel::kOff) return;
  static constexpr const char* kNames[] = {"debug", "info", "warn", "error"};
  const std::string shown = terminal_safe(message);
  std::lock_guard<std::mutex> lock(output_mutex());
  std::fprintf(stderr, "[%s] %.*s: %s\n", kNames[static_cast<int>(level)], static_cast<int>(component.size()),
               component.data(), shown.c_str());
}

}  // namespace a3::common
