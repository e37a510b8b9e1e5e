// Slice switching with a handover delay.
#include "linkemu/slice_selector.hpp"

#include <limits>
#include <stdexcept>

namespace a3::linkemu {

SliceSelector::SliceSelector(Slice initial, int64_t handover_delay_us)
    : active_(initial), handover_delay_us_(handover_delay_us) {
  if (handover_delay_us < 0) throw std::invalid_argument("handover delay must be >= 0");
}

Slice SliceSelector::active_at(int64_t now_us) {
  if (pending_ && now_us >= pending_effective_us_) {
    active_ = *pending_;
    pending_.reset();
    ++switches_done_;
  }
  return active_;
}

int64_t SliceSelector::pending_effective_us() const {
  return pending_ ? pending_effective_us_ : std::numeric_limits<int64_t>::max();
}

SwitchResult SliceSelector::request(Slice to, int64_t now_us) {
  SwitchResult result;
  result.from = active_at(now_us);
  result.to = to;
  if (pending_ && *pending_ == to) {
    result.note = "already pending";
    result.effective_us = pending_effective_us_;
    return result;
  }
  if (pending_) result.note = std::string("replaces the pending switch to ") + to_string(*pending_);
  if (to == active_) {
    pending_.reset();
    if (result.note.empty()) result.note = "already active";
    result.effective_us = now_us;
    return result;
  }
  pending_ = to;
  pending_effective_us_ = now_us + handover_delay_us_;
  result.effective_us = pending_effective_us_;
  if (handover_delay_us_ == 0) active_at(now_us);
  return result;
}

}  // namespace a3::linkemu
