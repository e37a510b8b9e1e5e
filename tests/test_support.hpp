// Helpers every test suite shares: where ../shared is, and skipping when it is absent.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace a3::test {

// The shared data folder: $A3_SHARED_DIR, else ../shared beside the repository.
inline std::filesystem::path shared_dir() {
  if (const char* env = std::getenv("A3_SHARED_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return A3_SHARED_DIR_DEFAULT;
}

inline std::filesystem::path source_dir() { return A3_SOURCE_DIR; }

inline std::string shared_missing_message(const std::filesystem::path& what) {
  return "needs " + what.string() +
         " (the α³-Bench public release and DroneCAN vectors in ../shared/); "
         "put them beside the repository or set A3_SHARED_DIR";
}

// An LCM UDP multicast URL on a port of this test process's own (from its pid), so test programs
// running side by side (ctest -j) or a user's rig never hear each other's messages. An even
// port: the next one carries the lockstep answers (answers_lcm_url).
inline std::string private_udpm_url() {
  return "udpm://239.255.76.67:" + std::to_string(27668 + 2 * (::getpid() % 10000)) + "?ttl=0";
}

}  // namespace a3::test

// Skips the current test when a file or folder under ../shared is absent.
#define A3_REQUIRE_SHARED(path_var, relative)                                   \
  const std::filesystem::path path_var = ::a3::test::shared_dir() / (relative); \
  if (!std::filesystem::exists(path_var)) {                                     \
    GTEST_SKIP() << ::a3::test::shared_missing_message(path_var);               \
  }
