// The integrators by name: the one list the command line, the run options and the benchmarks
// take their names from (dynamics/integrator.hpp makes them).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace a3::dynamics {

enum class IntegratorKind { kRk4, kCvode, kOde };
inline constexpr std::array<IntegratorKind, 3> kAllIntegrators = {IntegratorKind::kRk4, IntegratorKind::kCvode,
                                                                  IntegratorKind::kOde};
// "rk4" | "cvode" | "ode"; throws std::invalid_argument otherwise.
IntegratorKind parse_integrator_kind(const std::string& name);
const char* to_string(IntegratorKind kind);
// The names, in kAllIntegrators order, and the names to kinds (for command-line parsers).
std::vector<std::string> integrator_names();
std::map<std::string, IntegratorKind> integrator_by_name();

}  // namespace a3::dynamics
