// PNG files drawn by another program (gnuplot) into a temporary name, moved into place only
// when whole: gnuplot exits 0 even when a full disk cut its PNG short.
#pragma once

#include <filesystem>
#include <string>

namespace a3::common {

// ".tmp-<pid>", and "<png>.tmp-<pid>": where the drawing program writes.
std::string temporary_png_suffix();
std::filesystem::path temporary_png_path(const std::filesystem::path& png);

// True when the file ends with a PNG's end chunk (IEND).
bool png_is_complete(const std::filesystem::path& file);

// Checks that `temporary` is a whole PNG, syncs it and renames it to `png`. Otherwise removes
// it and throws OutputError: "<png>: incomplete PNG (<n> bytes, no end chunk; <m> bytes free)"
// or "<png>: <strerror>".
void commit_png(const std::filesystem::path& temporary, const std::filesystem::path& png);

}  // namespace a3::common
