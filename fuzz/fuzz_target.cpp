// The registry of fuzz target bodies (replay test) and require().
#include "fuzz/fuzz_target.hpp"

#include <cstdio>
#include <cstdlib>

namespace a3::fuzz {

std::map<std::string, TargetBody>& registered_targets() {
  static std::map<std::string, TargetBody> targets;
  return targets;
}

void require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

}  // namespace a3::fuzz
