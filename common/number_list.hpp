// A comma list of numbers in a spec string ("2.5,0.4" of "lognormal:2.5,0.4"), the one parser of
// it: every item a whole finite number, else std::invalid_argument naming the spec and the item.
#pragma once

#include <string>
#include <vector>

namespace a3::common {

struct NumberListRules {
  std::string what;            // the spec's kind, for errors: "think time", "latency"
  bool non_negative = false;   // refuse numbers below zero
};

std::vector<double> parse_number_list(const std::string& text, const std::string& spec, const NumberListRules& rules);

}  // namespace a3::common
