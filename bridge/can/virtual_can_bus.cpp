// Simulated CAN bus with arbitration and wire time (see virtual_can_bus.hpp).
#include "bridge/can/virtual_can_bus.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace a3::bridge {

struct VirtualCanBus::Impl {
  struct Pending {
    CanFrame frame;
    int64_t queued_ns;
  };
  struct Port {
    std::string name;
    bool started = false;
    common::Executor* executor = nullptr;
    CanFrameHandler handler;
    // Ordered by (arbitration key, sequence): the head is what this port offers the bus.
    std::map<std::pair<uint32_t, uint64_t>, Pending> queue;
    CanBusStats stats;
  };

  common::Executor& executor;
  VirtualCanBusConfig config;
  std::vector<Port*> ports;  // attach order, for deterministic ties
  bool busy = false;
  bool arbitration_scheduled = false;
  int64_t bus_free_ns = 0;
  uint64_t sequence = 0;
  VirtualCanBusStats stats;

  Impl(common::Executor& e, VirtualCanBusConfig c) : executor(e), config(c) {
    if (!(config.bit_rate_bps >= 1000.0 && config.bit_rate_bps <= 10e6)) {
      throw std::invalid_argument("VirtualCanBus: bit_rate_bps must be 1e3..1e7, not " +
                                  std::to_string(config.bit_rate_bps));
    }
    if (config.tx_queue_frames == 0) {
      throw std::invalid_argument("VirtualCanBus: tx_queue_frames must be at least 1");
    }
  }

  int64_t now_ns() const { return executor.clock().now_us() * 1000; }

  int64_t frame_ns(const CanFrame& frame) const {
    const double bits = can_frame_bits(frame, config.stuffing);
    return static_cast<int64_t>(std::llround(bits * 1e9 / config.bit_rate_bps));
  }

  bool enqueue(Port& port, const CanFrame& frame) {
    if (port.queue.size() >= config.tx_queue_frames) {
      ++port.stats.send_refused;
      return false;
    }
    port.queue.emplace(std::make_pair(can_arbitration_key(frame), sequence++),
                       Pending{frame, now_ns()});
    ++port.stats.frames_sent;
    port.stats.tx_queue_peak = std::max(port.stats.tx_queue_peak, port.queue.size());
    if (!busy && !arbitration_scheduled) schedule_arbitration(std::max(now_ns(), bus_free_ns));
    return true;
  }

  void schedule_arbitration(int64_t at_ns) {
    arbitration_scheduled = true;
    // Frames sent at this same instant (later in this event round) join the arbitration.
    std::weak_ptr<Impl> weak = self;
    executor.schedule_at((at_ns + 999) / 1000, [weak, at_ns] {
      if (auto impl = weak.lock()) impl->arbitrate(at_ns);
    });
  }

  void arbitrate(int64_t start_ns) {
    arbitration_scheduled = false;
    // A frame queued from a receive handler schedules an arbitration, and finish() then
    // arbitrates directly: the later of the two must not put a second frame on the wire.
    if (busy) return;
    Port* winner = nullptr;
    for (Port* port : ports) {
      if (port->queue.empty()) continue;
      if (winner == nullptr || port->queue.begin()->first.first < winner->queue.begin()->first.first) {
        winner = port;
      }
    }
    if (winner == nullptr) return;
    const auto head = winner->queue.begin();
    const CanFrame frame = head->second.frame;
    const int64_t delay = start_ns - head->second.queued_ns;
    winner->queue.erase(head);
    stats.max_queue_delay_ns = std::max(stats.max_queue_delay_ns, delay);
    stats.total_queue_delay_ns += delay;
    if (stats.first_frame_start_ns < 0) stats.first_frame_start_ns = start_ns;

    const int64_t duration = frame_ns(frame);
    const int64_t end_ns = start_ns + duration;
    busy = true;
    bus_free_ns = end_ns;
    ++stats.frames;
    stats.bits += can_frame_bits(frame, config.stuffing);
    stats.busy_ns += duration;
    std::weak_ptr<Impl> weak = self;
    executor.schedule_at((end_ns + 999) / 1000, [weak, frame, winner, end_ns] {
      if (auto impl = weak.lock()) impl->finish(frame, winner, end_ns);
    });
  }

  void finish(const CanFrame& frame, const Port* sender, int64_t end_ns) {
    busy = false;
    const int64_t rx_time_us = executor.clock().now_us();
    for (Port* port : ports) {
      if (port == sender || !port->started) continue;
      ++port->stats.frames_received;
      if (port->executor == &executor) {
        port->handler(frame, rx_time_us);
      } else {
        port->executor->schedule_at(port->executor->clock().now_us(),
                                    [handler = port->handler, frame, rx_time_us] {
                                      handler(frame, rx_time_us);
                                    });
      }
    }
    // The next frame starts right after this one's intermission (no rounding drift).
    for (Port* port : ports) {
      if (!port->queue.empty()) {
        arbitrate(end_ns);
        return;
      }
    }
  }

  std::weak_ptr<Impl> self;
};

namespace {

class VirtualCanPort final : public CanBus {
 public:
  VirtualCanPort(std::shared_ptr<VirtualCanBus::Impl> bus, const std::string& name) : bus_(bus) {
    port_.name = name;
    bus->ports.push_back(&port_);
  }
  ~VirtualCanPort() override {
    if (auto bus = bus_.lock()) {
      auto& ports = bus->ports;
      ports.erase(std::remove(ports.begin(), ports.end(), &port_), ports.end());
    }
  }

  std::string name() const override { return "virtual:" + port_.name; }
  bool send(const CanFrame& frame) override {
    auto bus = bus_.lock();
    if (!bus) {
      ++port_.stats.send_refused;
      return false;
    }
    return bus->enqueue(port_, frame);
  }
  void start(common::Executor& executor, CanFrameHandler handler) override {
    port_.executor = &executor;
    port_.handler = std::move(handler);
    port_.started = true;
  }
  void stop() override { port_.started = false; }
  std::size_t tx_pending() const override { return port_.queue.size(); }
  CanBusStats stats() const override { return port_.stats; }

 private:
  std::weak_ptr<VirtualCanBus::Impl> bus_;
  VirtualCanBus::Impl::Port port_;
};

}  // namespace

double VirtualCanBusStats::load(int64_t now_us) const {
  const int64_t span_ns = now_us * 1000 - first_frame_start_ns;
  if (frames == 0 || span_ns <= 0) return 0.0;
  return std::min(1.0, static_cast<double>(busy_ns) / static_cast<double>(span_ns));
}

VirtualCanBus::VirtualCanBus(common::Executor& executor, VirtualCanBusConfig config)
    : impl_(std::make_shared<Impl>(executor, config)) {
  impl_->self = impl_;
}

VirtualCanBus::~VirtualCanBus() = default;

std::unique_ptr<CanBus> VirtualCanBus::attach(const std::string& port_name) {
  return std::make_unique<VirtualCanPort>(impl_, port_name);
}

const VirtualCanBusConfig& VirtualCanBus::config() const { return impl_->config; }

VirtualCanBusStats VirtualCanBus::stats() const { return impl_->stats; }

int64_t VirtualCanBus::frame_time_ns(const CanFrame& frame) const { return impl_->frame_ns(frame); }

}  // namespace a3::bridge
