// A tmpfs of a given size mounted on a fresh folder, for tests of a full disk. Mounting needs
// root (CAP_SYS_ADMIN); when it fails, skip_reason() says why and the test skips with it.
#pragma once

#include <stdlib.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace a3::test {

class TinyTmpfs {
 public:
  explicit TinyTmpfs(std::uint64_t size_bytes) {
    std::string pattern = (std::filesystem::temp_directory_path() / "a3rig-tmpfs-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed: " + std::string(std::strerror(errno)));
    path_ = pattern;
    if (::geteuid() != 0) {
      skip_reason_ = "a full filesystem needs a tmpfs mount, which needs root (running as uid " +
                     std::to_string(::geteuid()) + ")";
      return;
    }
    const std::string options = "size=" + std::to_string(size_bytes);
    if (::mount("tmpfs", path_.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      skip_reason_ = "mount -t tmpfs -o " + options + " " + path_.string() + ": " + std::strerror(errno);
      return;
    }
    mounted_ = true;
  }
  ~TinyTmpfs() {
    if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TinyTmpfs(const TinyTmpfs&) = delete;
  TinyTmpfs& operator=(const TinyTmpfs&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::string& skip_reason() const { return skip_reason_; }

 private:
  std::filesystem::path path_;
  std::string skip_reason_;
  bool mounted_ = false;
};

}  // namespace a3::test
