// Drop-reason names and the one-line summary.
#include "linkemu/link_stats.hpp"

#include <sstream>

namespace a3::linkemu {

const char* to_string(DropReason reason) {
  switch (reason) {
    case DropReason::kUndecodable: return "undecodable";
    case DropReason::kBadSize: return "bad_size";
    case DropReason::kOversized: return "oversized";
    case DropReason::kQueueFull: return "queue_full";
  }
  return "?";
}

uint64_t DirectionStats::dropped_total() const {
  uint64_t total = 0;
  for (uint64_t n : dropped) total += n;
  return total;
}

std::string summary(const LinkStats& stats) {
  std::ostringstream out;
  const auto direction = [&](const char* name, const DirectionStats& d) {
    out << name << ": " << d.received << " in, " << d.delivered << " delivered, " << d.lost
        << " lost, " << d.dropped_total() << " dropped";
    bool first = true;
    for (std::size_t i = 0; i < kDropReasonCount; ++i) {
      if (d.dropped[i] == 0) continue;
      out << (first ? " (" : ", ") << to_string(static_cast<DropReason>(i)) << " " << d.dropped[i];
      first = false;
    }
    if (!first) out << ")";
    out << ", " << d.pending << " in flight";
  };
  direction("up", stats.up);
  out << "; ";
  direction("down", stats.down);
  out << "; " << stats.slice_switch_requests << " slice requests, " << stats.edge_requests
      << " edge requests";
  return out.str();
}

}  // namespace a3::linkemu
