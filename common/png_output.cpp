// Whole-or-absent PNG files from gnuplot.
#include "common/png_output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "common/atomic_file.hpp"

namespace a3::common {
namespace fs = std::filesystem;

std::string temporary_png_suffix() { return ".tmp-" + std::to_string(::getpid()); }

fs::path temporary_png_path(const fs::path& png) { return png.string() + temporary_png_suffix(); }

bool png_is_complete(const fs::path& file) {
  static const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < static_cast<std::streamoff>(kIend.size())) return false;
  in.seekg(-static_cast<std::streamoff>(kIend.size()), std::ios::end);
  std::string tail(kIend.size(), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  return in && tail == kIend;
}

void commit_png(const fs::path& temporary, const fs::path& png) {
  if (!png_is_complete(temporary)) {
    std::error_code ec;
    const auto size = fs::file_size(temporary, ec);
    ::unlink(temporary.c_str());
    throw OutputError(png.string() + ": incomplete PNG (" + std::to_string(ec ? 0 : size) + " bytes, no end chunk; " +
                      std::to_string(free_bytes_at(png.parent_path())) + " bytes free)");
  }
  const int fd = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
  int error_number = fd < 0 ? errno : 0;
  if (fd >= 0 && ::fsync(fd) != 0) error_number = errno;
  if (fd >= 0) ::close(fd);
  if (error_number == 0 && ::rename(temporary.c_str(), png.c_str()) != 0) error_number = errno;
  if (error_number != 0) {
    ::unlink(temporary.c_str());
    throw OutputError(png.string() + ": " + std::strerror(error_number));
  }
}

}  // namespace a3::common
