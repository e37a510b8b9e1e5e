// Running gnuplot on a script the rig wrote, and writing outside text into such a script so
// that gnuplot reads it as text and never as a command.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace a3::common {

// A gnuplot string expression for `text` made of single-quoted literals, inside which gnuplot
// performs no substitution (no `...` command, no @macro, no escapes): a quote in the text is
// joined in as "'" ('it'."'".'s'), and a line break (which would end the command) becomes a space.
std::string gnuplot_string(std::string_view text);

// A label in a data file that gnuplot reads (a column of a TSV or space-separated table):
// between double quotes, with quotes, tabs and line breaks (which would shift the columns) as spaces.
std::string gnuplot_data_label(std::string_view text);

// True when a program named gnuplot is on PATH.
bool gnuplot_found();

// Runs `gnuplot -e ASSIGNMENT... SCRIPT` directly (no shell), its standard output and error
// into `log`, and waits for it. Throws std::runtime_error when it cannot be started (naming the
// Debian package) or exits non-zero (with its log).
void run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& log,
                 const std::vector<std::string>& assignments);

}  // namespace a3::common
