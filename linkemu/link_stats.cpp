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

DirectionStats::DirectionStats(common::CounterSet& set, const std::string& direction)
    : received(set.add(direction + ".received")),
      delivered(set.add(direction + ".delivered")),
      lost(set.add(direction + ".lost")),
      bytes_delivered(set.add(direction + ".bytes_delivered")),
      pending(set.add(direction + ".pending")),
      max_pending(set.add(direction + ".max_pending")) {
  for (std::size_t r = 0; r < kDropReasonCount; ++r) {
    dropped.counters[r] = &set.add(direction + ".dropped." + to_string(static_cast<DropReason>(r)));
  }
}

uint64_t DirectionStats::dropped_total() const {
  uint64_t total = 0;
  for (const common::Counter* n : dropped.counters) total += n->value();
  return total;
}

LinkStats::LinkStats(common::CounterSet& set)
    : up(set, "up"),
      down(set, "down"),
      slice_switch_requests(set.add("slice_switch_requests")),
      edge_requests(set.add("edge_requests")),
      net_published(set.add("net_published")),
      records(set.add("records")) {}

std::string summary(const LinkStats& stats) {
  std::ostringstream out;
  const auto direction = [&](const char* name, const DirectionStats& d) {
    out << name << ": " << d.received.value() << " in, " << d.delivered.value() << " delivered, " << d.lost.value()
        << " lost, " << d.dropped_total() << " dropped";
    bool first = true;
    for (std::size_t i = 0; i < kDropReasonCount; ++i) {
      if (d.dropped[i].value() == 0) continue;
      out << (first ? " (" : ", ") << to_string(static_cast<DropReason>(i)) << " " << d.dropped[i].value();
      first = false;
    }
    if (!first) out << ")";
    out << ", " << d.pending.value() << " in flight";
  };
  direction("up", stats.up);
  out << "; ";
  direction("down", stats.down);
  out << "; " << stats.slice_switch_requests.value() << " slice requests, " << stats.edge_requests.value()
      << " edge requests";
  return out.str();
}

}  // namespace a3::linkemu
