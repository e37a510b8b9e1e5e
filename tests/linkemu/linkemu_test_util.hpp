// Helpers for the linkemu suites: the SPEC §6 figures (written out here, so the profile
// file cannot drift from the SPEC unnoticed), sample statistics, constant traces, and a
// client node that sends link messages at given times and records everything it hears.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "a3lcm/edge_compute_reply_t.hpp"
#include "a3lcm/link_message_t.hpp"
#include "a3lcm/link_record_t.hpp"
#include "a3lcm/network_state_t.hpp"
#include "a3lcm/slice_switch_reply_t.hpp"
#include "common/bus.hpp"
#include "common/executor.hpp"
#include "common/node.hpp"
#include "linkemu/link_emulator_config.hpp"
#include "linkemu/network_state.hpp"
#include "linkemu/network_trace.hpp"

namespace a3::linkemu::test {

// SPEC-alpha3.md §6.
struct SpecRow {
  Slice slice;
  double lat_mean_ms, lat_median_ms, lat_p90_ms, jitter_mean_ms, loss_mean_pct,
      throughput_mean_mbps, edge_load_mean;
};
inline const std::vector<SpecRow>& spec_rows() {
  static const std::vector<SpecRow> rows = {
      {Slice::kUrllc, 7.23, 7.00, 9.10, 1.11, 0.059, 95.2, 0.360},
      {Slice::kEmbb, 21.47, 14.00, 25.00, 4.72, 0.642, 608.0, 0.517},
      {Slice::kMmtc, 72.98, 50.00, 150.00, 17.10, 2.387, 2.3, 0.757},
  };
  return rows;
}

inline double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

// Empirical quantile (nearest rank on a sorted copy).
inline double quantile_of(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(k, v.size() - 1)];
}

inline double relative_error(double got, double want) { return std::abs(got / want - 1.0); }

inline NetworkState make_state(Slice slice, double lat_ms, double jitter_ms, double loss_pct,
                               double throughput_mbps, double edge_load) {
  NetworkState s;
  s.slice = slice;
  s.lat_ms = lat_ms;
  s.jitter_ms = jitter_ms;
  s.loss_pct = loss_pct;
  s.throughput_mbps = throughput_mbps;
  s.edge_load = edge_load;
  s.degraded = is_hard(s);
  return s;
}

// A one-point trace: n_t fixed for the whole run.
inline NetworkTrace constant_trace(const NetworkState& state) {
  NetworkTrace trace;
  trace.points.push_back({0, state});
  trace.last_hold_us = 1'000'000;
  trace.source = "constant test trace";
  return trace;
}

inline a3lcm::link_message_t make_message(int64_t id, const std::string& sender,
                                          std::size_t payload_bytes, int32_t charged_bytes = 0) {
  a3lcm::link_message_t m{};
  m.message_id = id;
  m.sender = sender;
  m.kind = "test";
  m.payload.resize(payload_bytes);
  for (std::size_t i = 0; i < payload_bytes; ++i) m.payload[i] = static_cast<uint8_t>((i * 31 + id) & 0xFF);
  m.payload_length = static_cast<int32_t>(payload_bytes);
  m.payload_size_bytes = charged_bytes;
  return m;
}

struct Received {
  int64_t recv_us;
  a3lcm::link_message_t message;
};

// Sends scheduled messages on the TX channels and records what comes back on every
// channel the link emulator publishes.
class ClientNode final : public common::Node {
 public:
  explicit ClientNode(LinkChannels channels = {}) : channels_(std::move(channels)) {}
  std::string name() const override { return "client"; }

  // Before start(): send `message` on the up (or down) TX channel at t_us.
  void send_at(int64_t t_us, bool up, a3lcm::link_message_t message) {
    planned_.push_back({t_us, up, std::move(message)});
  }
  // Before start(): run fn(executor, bus) at t_us (slice requests, edge requests, raw bytes).
  void at(int64_t t_us, std::function<void(common::Executor&, common::Bus&)> fn) {
    actions_.push_back({t_us, std::move(fn)});
  }

  void start(common::Executor& executor, common::Bus& bus) override {
    bus.subscribe<a3lcm::link_message_t>(channels_.up_rx, [this](const a3lcm::link_message_t& m, int64_t t) {
      up_rx.push_back({t, m});
    });
    bus.subscribe<a3lcm::link_message_t>(channels_.down_rx, [this](const a3lcm::link_message_t& m, int64_t t) {
      down_rx.push_back({t, m});
    });
    bus.subscribe<a3lcm::network_state_t>(channels_.net, [this](const a3lcm::network_state_t& m, int64_t) {
      net.push_back(m);
    });
    bus.subscribe<a3lcm::link_record_t>(channels_.record, [this](const a3lcm::link_record_t& m, int64_t) {
      records.push_back(m);
    });
    bus.subscribe<a3lcm::slice_switch_reply_t>(channels_.slice_reply, [this](const a3lcm::slice_switch_reply_t& m, int64_t) {
      slice_replies.push_back(m);
    });
    bus.subscribe<a3lcm::edge_compute_reply_t>(channels_.edge_reply, [this](const a3lcm::edge_compute_reply_t& m, int64_t) {
      edge_replies.push_back(m);
    });
    for (auto& p : planned_) {
      executor.schedule_at(p.t_us, [this, &executor, &bus, &p] {
        p.message.utime_us = p.message.sent_utime_us = executor.clock().now_us();
        bus.publish(p.up ? channels_.up_tx : channels_.down_tx, p.message);
        ++sent;
      });
    }
    for (auto& a : actions_) {
      executor.schedule_at(a.t_us, [&executor, &bus, &a] { a.fn(executor, bus); });
    }
  }

  std::vector<Received> up_rx, down_rx;
  std::vector<a3lcm::network_state_t> net;
  std::vector<a3lcm::link_record_t> records;
  std::vector<a3lcm::slice_switch_reply_t> slice_replies;
  std::vector<a3lcm::edge_compute_reply_t> edge_replies;
  uint64_t sent = 0;

 private:
  struct Planned {
    int64_t t_us;
    bool up;
    a3lcm::link_message_t message;
  };
  struct Action {
    int64_t t_us;
    std::function<void(common::Executor&, common::Bus&)> fn;
  };
  LinkChannels channels_;
  std::vector<Planned> planned_;
  std::vector<Action> actions_;
};

}  // namespace a3::linkemu::test
