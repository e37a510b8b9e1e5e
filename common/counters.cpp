// Named counters.
#include "common/counters.hpp"

#include <stdexcept>
#include <tuple>

namespace a3::common {

Counter& CounterSet::add(std::string name) {
  for (const auto& [known, counter] : counters_) {
    if (known == name) throw std::logic_error("counter '" + name + "' registered twice");
  }
  counters_.emplace_back(std::piecewise_construct, std::forward_as_tuple(std::move(name)), std::forward_as_tuple());
  return counters_.back().second;
}

uint64_t CounterSet::get(std::string_view name) const {
  for (const auto& [known, counter] : counters_) {
    if (known == name) return counter.value();
  }
  throw std::out_of_range("no counter named '" + std::string(name) + "'");
}

std::vector<std::pair<std::string, uint64_t>> CounterSet::snapshot() const {
  std::vector<std::pair<std::string, uint64_t>> out;
  out.reserve(counters_.size());
  for (const auto& [name, counter] : counters_) out.emplace_back(name, counter.value());
  return out;
}

std::string to_text(const CounterSet& counters) {
  std::string out;
  for (const auto& [name, value] : counters.snapshot()) {
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(value);
  }
  return out;
}

}  // namespace a3::common
