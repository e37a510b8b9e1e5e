// Where n_t comes from: the seeded process of the slice profiles (SyntheticNetwork) or a
// recorded trace (TraceReplay). The link emulator asks it for the state of the active
// slice at the times messages are sent, and for when that state changes next.
#pragma once

#include <cstdint>
#include <string>

#include "linkemu/network_state.hpp"

namespace a3::linkemu {

class NetworkStateSource {
 public:
  virtual ~NetworkStateSource() = default;
  // n_t at t_us while `slice` is the active slice. Times are non-decreasing per slice.
  virtual NetworkState state_at(Slice slice, int64_t t_us) = 0;
  // When the state last returned for `slice` changes next (INT64_MAX: never).
  virtual int64_t next_change_us(Slice slice) const = 0;
  // True when the source decides the slice itself (a trace): switch requests are refused.
  virtual bool dictates_slice() const = 0;
  // One line for logs: what the source is.
  virtual std::string describe() const = 0;
};

}  // namespace a3::linkemu
