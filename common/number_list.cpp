// Comma lists of numbers.
#include "common/number_list.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace a3::common {

std::vector<double> parse_number_list(const std::string& text, const std::string& spec, const NumberListRules& rules) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const double x = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(x) || (rules.non_negative && x < 0.0)) throw std::invalid_argument("");
      out.push_back(x);
    } catch (const std::exception&) {
      throw std::invalid_argument(rules.what + " '" + spec + "': '" + item + "' is not a " +
                                  (rules.non_negative ? "non-negative number" : "number"));
    }
  }
  return out;
}

}  // namespace a3::common
