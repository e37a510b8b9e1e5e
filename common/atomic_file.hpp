// Output files that are either whole or absent: written to "<name>.tmp-<pid>" beside the
// target, flushed (fsync), then renamed over it. A failed write (a full disk: ENOSPC) removes
// the temporary file and throws OutputError naming the file and the reason.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace a3::common {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Creates the parent folders if missing (OutputError with the reason when it cannot).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// For files written piece by piece (logs, tables): nothing appears at `path` until commit().
// Every write checks its result; the first failure throws OutputError at once.
// Destroyed without commit(): the temporary file is removed.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::filesystem::path path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view bytes);
  void commit();  // fsync + rename; throws OutputError
  std::uint64_t bytes_written() const { return bytes_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  std::uint64_t bytes_ = 0;
};

// Free bytes on the filesystem holding `folder` (or its nearest existing ancestor).
std::uint64_t free_bytes_at(const std::filesystem::path& folder);

}  // namespace a3::common
