// Turn → episode JSON.
#include "agent/conversation/turn.hpp"

namespace a3::agent {

nlohmann::json Turn::to_json() const {
  return {{"turn", number}, {"speaker", speaker}, {"intent", intent},
          {"actions", actions}, {"obs", obs},   {"net", net}};
}

}  // namespace a3::agent
