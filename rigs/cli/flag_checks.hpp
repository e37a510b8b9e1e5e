// Checks of numeric and folder flags whose failure reads as one line with human bounds:
// "--rtf: must be > 0 (got -1)", "--node-id: must be from 1 to 127 (got 300)",
// "--out: out/x is a file, not a folder". (CLI11's own PositiveNumber and Range print the
// largest double, 309 digits, as the bound.) CLI11 puts the flag's name in front.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

namespace a3::rigs {

inline std::string bound_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// The value as a finite number, or nothing (CLI11 reports unconvertible text itself).
inline bool read_number(const std::string& text, double& value) {
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    return used == text.size() && std::isfinite(value);
  } catch (const std::exception&) {
    return false;
  }
}

inline CLI::Validator number_check(const std::string& description, bool (*ok)(double, double, double), double lo,
                                   double hi) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0.0;
        if (!read_number(text, value)) return "must be a number " + description + " (got '" + text + "')";
        return ok(value, lo, hi) ? "" : "must be " + description + " (got " + text + ")";
      },
      description);
}

inline CLI::Validator positive() {
  return number_check("> 0", [](double v, double, double) { return v > 0.0; }, 0.0, 0.0);
}

inline CLI::Validator non_negative() {
  return number_check(">= 0", [](double v, double, double) { return v >= 0.0; }, 0.0, 0.0);
}

// lo <= value <= hi.
inline CLI::Validator between(double lo, double hi) {
  return number_check("from " + bound_text(lo) + " to " + bound_text(hi),
                      [](double v, double l, double h) { return v >= l && v <= h; }, lo, hi);
}

// A folder the command will write into: absent (it is created), or a folder; refused when it
// or a parent exists as something else.
inline CLI::Validator output_folder() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty()) return "must name a folder (got an empty path)";
        std::error_code ec;
        for (std::filesystem::path p = text; !p.empty(); p = p.parent_path()) {
          const auto status = std::filesystem::status(p, ec);
          if (std::filesystem::exists(status) && !std::filesystem::is_directory(status)) {
            return p == std::filesystem::path(text) ? text + " is a file, not a folder"
                                                    : "cannot create " + text + ": " + p.string() + " is a file, not a folder";
          }
          if (p == p.parent_path()) break;
        }
        return "";
      },
      "FOLDER");
}

}  // namespace a3::rigs
