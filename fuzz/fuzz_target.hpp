// One fuzz target's body, written once for two programs: the libFuzzer program fuzz_<name>
// (built with A3_LIBFUZZER: the body becomes LLVMFuzzerTestOneInput) and the replay test
// (tests/fuzz), which registers every body by name and runs the stored inputs through it.
// A body must not throw and must not abort on any input: a finding is a sanitizer report, an
// escaped exception, or a broken invariant stopped with require().
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>

namespace a3::fuzz {

using Input = std::span<const std::uint8_t>;
using TargetBody = void (*)(Input);

// Every body linked into the replay program, by target name.
std::map<std::string, TargetBody>& registered_targets();

struct TargetRegistration {
  TargetRegistration(const char* name, TargetBody body) { registered_targets()[name] = body; }
};

// Stops the program (a finding) with `what` on stderr when `condition` is false.
void require(bool condition, const char* what);

}  // namespace a3::fuzz

#ifdef A3_LIBFUZZER
#define A3_FUZZ_TARGET(name)                                                         \
  static void a3_fuzz_body_##name(a3::fuzz::Input input);                            \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    a3_fuzz_body_##name(a3::fuzz::Input(data, size));                                \
    return 0;                                                                        \
  }                                                                                  \
  static void a3_fuzz_body_##name(a3::fuzz::Input input)
#else
#define A3_FUZZ_TARGET(name)                                                                      \
  static void a3_fuzz_body_##name(a3::fuzz::Input input);                                         \
  static const a3::fuzz::TargetRegistration a3_fuzz_registration_##name{#name, a3_fuzz_body_##name}; \
  static void a3_fuzz_body_##name(a3::fuzz::Input input)
#endif
