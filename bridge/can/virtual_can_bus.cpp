// Simulated CAN bus with arbitration and wire time (see virtual_can_bus.hpp).
#include "bridge/can/virtual_can_bus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace a3::bridge {

struct VirtualCanBus::Impl {
  struct Pending {
    uint32_t key;  // arbitration key
    CanFrame frame;
    int64_t queued_ns;
  };
  // A port's frames waiting for the bus in arbitration order: by key, and in the order sent
  // among equal keys. Nearly a FIFO (a transfer's frames share a key), so it is a sorted
  // vector read from an index: a frame is appended and slid back past the later keys only;
  // the storage is reused, and the consumed front dropped once it is most of it.
  class PendingFrames {
   public:
    bool empty() const { return head_ == items_.size(); }
    std::size_t size() const { return items_.size() - head_; }
    const Pending& front() const { return items_[head_]; }
    void push(const Pending& pending) {
      if (head_ == items_.size()) {
        items_.clear();
        head_ = 0;
      } else if (head_ >= 64 && 2 * head_ >= items_.size()) {
        items_.erase(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(head_));
        head_ = 0;
      }
      items_.push_back(pending);
      for (std::size_t i = items_.size() - 1; i > head_ && items_[i - 1].key > pending.key; --i) {
        std::swap(items_[i - 1], items_[i]);
      }
    }
    Pending pop() { return items_[head_++]; }

   private:
    std::vector<Pending> items_;
    std::size_t head_ = 0;  // the first frame still waiting
  };
  struct Port {
    // The bus while it exists (its destructor clears this): a plain pointer, because send()
    // runs for every frame and locking a weak_ptr costs two atomic operations.
    Impl* bus = nullptr;
    std::string name;
    bool started = false;
    common::Executor* executor = nullptr;
    CanFrameHandler handler;
    PendingFrames queue;
    CanBusStats stats;
  };
  // The frame on the wire: one at a time.
  struct InFlight {
    CanFrame frame;
    const Port* sender = nullptr;
    int64_t end_ns = 0;
  };

  common::Executor& executor;
  VirtualCanBusConfig config;
  std::vector<Port*> ports;  // attach order, for deterministic ties
  bool busy = false;
  bool arbitration_scheduled = false;
  int64_t bus_free_ns = 0;
  VirtualCanBusStats stats;
  InFlight in_flight;
  // The bus's pending events, cancelled when it goes; their callbacks capture only `this`,
  // small enough for std::function to hold without allocating.
  common::TimerId arbitration_timer = 0;
  common::TimerId finish_timer = 0;
  // A bit's time when the bit rate is a whole number of bits per second dividing 1e9 (1 Mbit/s:
  // 1000 ns), else 0. Then bits_ns's product is what the rounded division gives (both exact).
  int64_t ns_per_bit = 0;

  Impl(common::Executor& e, VirtualCanBusConfig c) : executor(e), config(c) {
    if (!(config.bit_rate_bps >= 1000.0 && config.bit_rate_bps <= 10e6)) {
      throw std::invalid_argument("VirtualCanBus: bit_rate_bps must be 1e3..1e7, not " +
                                  std::to_string(config.bit_rate_bps));
    }
    if (config.tx_queue_frames == 0) {
      throw std::invalid_argument("VirtualCanBus: tx_queue_frames must be at least 1");
    }
    const double rate = config.bit_rate_bps;
    if (rate == std::floor(rate) && 1'000'000'000 % static_cast<int64_t>(rate) == 0) {
      ns_per_bit = 1'000'000'000 / static_cast<int64_t>(rate);
    }
  }
  ~Impl() {
    if (arbitration_scheduled) executor.cancel(arbitration_timer);
    if (busy) executor.cancel(finish_timer);
    for (Port* port : ports) port->bus = nullptr;
  }

  int64_t now_ns() const { return executor.clock().now_us() * 1000; }

  int64_t bits_ns(unsigned bits) const {
    if (ns_per_bit != 0) return ns_per_bit * bits;
    return static_cast<int64_t>(std::llround(static_cast<double>(bits) * 1e9 / config.bit_rate_bps));
  }
  int64_t frame_ns(const CanFrame& frame) const { return bits_ns(can_frame_bits(frame, config.stuffing)); }

  bool enqueue(Port& port, const CanFrame& frame) {
    if (port.queue.size() >= config.tx_queue_frames) {
      ++port.stats.send_refused;
      return false;
    }
    port.queue.push(Pending{can_arbitration_key(frame), frame, now_ns()});
    ++port.stats.frames_sent;
    port.stats.tx_queue_peak = std::max(port.stats.tx_queue_peak, port.queue.size());
    if (!busy && !arbitration_scheduled) schedule_arbitration(std::max(now_ns(), bus_free_ns));
    return true;
  }

  void schedule_arbitration(int64_t at_ns) {
    arbitration_scheduled = true;
    // Frames sent at this same instant (later in this event round) join the arbitration.
    arbitration_timer = executor.schedule_at((at_ns + 999) / 1000, [this, at_ns] {
      arbitration_scheduled = false;
      arbitrate(at_ns);
    });
  }

  Port* arbitration_winner() const {
    Port* winner = nullptr;
    for (Port* port : ports) {
      if (port->queue.empty()) continue;
      if (winner == nullptr || port->queue.front().key < winner->queue.front().key) winner = port;
    }
    return winner;
  }

  // A frame queued from a receive handler schedules an arbitration, and finish() then
  // arbitrates directly: the later of the two must not put a second frame on the wire.
  void arbitrate(int64_t start_ns) {
    if (busy) return;
    Port* winner = arbitration_winner();
    if (winner == nullptr) return;
    const Pending head = winner->queue.pop();
    const int64_t delay = start_ns - head.queued_ns;
    stats.max_queue_delay_ns = std::max(stats.max_queue_delay_ns, delay);
    stats.total_queue_delay_ns += delay;
    if (stats.first_frame_start_ns < 0) stats.first_frame_start_ns = start_ns;

    const unsigned bits = can_frame_bits(head.frame, config.stuffing);
    const int64_t duration = bits_ns(bits);
    in_flight = InFlight{head.frame, winner, start_ns + duration};
    busy = true;
    bus_free_ns = in_flight.end_ns;
    ++stats.frames;
    stats.bits += bits;
    stats.busy_ns += duration;
    finish_timer = executor.schedule_at((in_flight.end_ns + 999) / 1000, [this] { finish(); });
  }

  void deliver(const CanFrame& frame, const Port* sender) {
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
  }

  void finish() {
    busy = false;
    const InFlight done = in_flight;  // handlers may put the next frame on the wire
    deliver(done.frame, done.sender);
    // The next frame starts right after this one's intermission (no rounding drift).
    for (Port* port : ports) {
      if (!port->queue.empty()) {
        arbitrate(done.end_ns);
        return;
      }
    }
  }
};

namespace {

class VirtualCanPort final : public CanBus {
 public:
  VirtualCanPort(VirtualCanBus::Impl& bus, const std::string& name) {
    port_.bus = &bus;
    port_.name = name;
    bus.ports.push_back(&port_);
  }
  ~VirtualCanPort() override {
    if (VirtualCanBus::Impl* bus = port_.bus) {
      auto& ports = bus->ports;
      ports.erase(std::remove(ports.begin(), ports.end(), &port_), ports.end());
    }
  }

  std::string name() const override { return "virtual:" + port_.name; }
  bool send(const CanFrame& frame) override {
    if (port_.bus == nullptr) {
      ++port_.stats.send_refused;
      return false;
    }
    return port_.bus->enqueue(port_, frame);
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
  VirtualCanBus::Impl::Port port_;
};

}  // namespace

double VirtualCanBusStats::load(int64_t now_us) const {
  const int64_t span_ns = now_us * 1000 - first_frame_start_ns;
  if (frames == 0 || span_ns <= 0) return 0.0;
  return std::min(1.0, static_cast<double>(busy_ns) / static_cast<double>(span_ns));
}

VirtualCanBus::VirtualCanBus(common::Executor& executor, VirtualCanBusConfig config)
    : impl_(std::make_shared<Impl>(executor, config)) {}

VirtualCanBus::~VirtualCanBus() = default;

std::unique_ptr<CanBus> VirtualCanBus::attach(const std::string& port_name) {
  return std::make_unique<VirtualCanPort>(*impl_, port_name);
}

const VirtualCanBusConfig& VirtualCanBus::config() const { return impl_->config; }

VirtualCanBusStats VirtualCanBus::stats() const { return impl_->stats; }

int64_t VirtualCanBus::frame_time_ns(const CanFrame& frame) const { return impl_->frame_ns(frame); }

}  // namespace a3::bridge
