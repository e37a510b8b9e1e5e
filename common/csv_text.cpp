// CSV cells and lines (csv_text.hpp).
#include "common/csv_text.hpp"

#include <regex>
#include <stdexcept>

namespace a3::common {
namespace {

constexpr char kGuard = '\'';

bool is_plain_number(std::string_view text) {
  static const std::regex kNumber(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
  return std::regex_match(text.begin(), text.end(), kNumber);
}

// Text a spreadsheet would read as a formula (or whose apostrophe would be taken for the guard).
bool needs_guard(std::string_view text) {
  if (text.empty()) return false;
  switch (text.front()) {
    case '=': case '+': case '-': case '@': case '\t': case '\r': return !is_plain_number(text);
    case kGuard: return true;
    default: return false;
  }
}

}  // namespace

std::string csv_cell(std::string_view text) {
  const bool guard = needs_guard(text);
  if (!guard && text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  if (guard) out += kGuard;
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::vector<std::string> csv_fields(std::string_view line) {
  std::vector<std::string> fields(1);
  std::vector<bool> was_quoted(1, false);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
      was_quoted.back() = true;
    } else if (c == ',') {
      fields.emplace_back();
      was_quoted.push_back(false);
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  if (quoted) throw std::invalid_argument("unterminated quoted field");
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (was_quoted[i] && !fields[i].empty() && fields[i].front() == kGuard) fields[i].erase(0, 1);
  }
  return fields;
}

}  // namespace a3::common
