// printf-style formatting of numbers into a std::string, for messages and briefs ("%.1f m"),
// sized to fit. Every argument is passed as a double, so the format's conversions are all
// floating-point ones (%f, %g, %e). The one helper for it: files keep no snprintf wrappers.
#pragma once

#include <cstdio>
#include <string>
#include <type_traits>

namespace a3::common {

template <typename... Numbers>
  requires(sizeof...(Numbers) > 0 && (std::is_arithmetic_v<Numbers> && ...))
std::string formatted(const char* format, Numbers... numbers) {
  const int size = std::snprintf(nullptr, 0, format, static_cast<double>(numbers)...);
  if (size <= 0) return "";
  std::string text(static_cast<std::size_t>(size), '\0');
  std::snprintf(text.data(), text.size() + 1, format, static_cast<double>(numbers)...);
  return text;
}

// The counts at which a repeated event is logged: 1, 10, 100, ... (a log that thins out).
inline bool is_power_of_ten(unsigned long long n) {
  while (n >= 10 && n % 10 == 0) n /= 10;
  return n == 1;
}

}  // namespace a3::common
