// The active slice and switch requests: a requested slice takes effect handover_delay
// after the request; until then the old slice carries the traffic. A later request
// replaces a pending one; asking for the active slice cancels a pending switch.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "linkemu/network_state.hpp"

namespace a3::linkemu {

struct SwitchResult {
  bool accepted = true;
  std::string note;  // what happened to an earlier pending request, or ""
  Slice from = Slice::kEmbb;
  Slice to = Slice::kEmbb;
  int64_t effective_us = 0;
};

class SliceSelector {
 public:
  SliceSelector(Slice initial, int64_t handover_delay_us);

  SwitchResult request(Slice to, int64_t now_us);
  // The slice in effect at now_us (a due pending switch is applied first).
  Slice active_at(int64_t now_us);
  std::optional<Slice> pending() const { return pending_; }
  // INT64_MAX when nothing is pending.
  int64_t pending_effective_us() const;
  uint64_t switches_done() const { return switches_done_; }

 private:
  Slice active_;
  int64_t handover_delay_us_;
  std::optional<Slice> pending_;
  int64_t pending_effective_us_ = 0;
  uint64_t switches_done_ = 0;
};

}  // namespace a3::linkemu
