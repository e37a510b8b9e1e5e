// One CSV dialect for every table the rig writes (results.csv, aggregate.csv, the score's
// per-episode and leaderboard tables): RFC 4180 quoting, and text that a spreadsheet would run
// as a formula kept as text.
//
// A cell whose text begins with '=', '+', '-', '@', a tab or a carriage return (OWASP's "CSV
// injection" leads) and is not a plain decimal number is written quoted with a leading
// apostrophe ("'=HYPERLINK(...)"), which LibreOffice and Excel show as text; so is a text that
// begins with an apostrophe itself, so that reading back (csv_fields) is exact.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace a3::common {

// The cell for `text`: as it is when it needs nothing, else quoted (and guarded, above).
std::string csv_cell(std::string_view text);

// The text of each cell of one line (no line break inside): quotes and the guard's apostrophe
// removed. Throws std::invalid_argument on an unterminated quote.
std::vector<std::string> csv_fields(std::string_view line);

}  // namespace a3::common
