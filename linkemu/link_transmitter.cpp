// Queueing, serialization, latency with jitter, loss, FIFO.
#include "linkemu/link_transmitter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace a3::linkemu {

double sample_message_latency_ms(common::Rng& rng, const NetworkState& state) {
  const double e = rng.exponential(1.0);
  return std::max(0.0, state.lat_ms + state.jitter_ms * (e - 1.0));
}

int64_t serialization_us(int64_t size_bytes, double throughput_mbps) {
  // 1 Mbit/s is one bit per microsecond.
  return static_cast<int64_t>(std::ceil(static_cast<double>(size_bytes) * 8.0 / throughput_mbps));
}

LinkTransmitter::LinkTransmitter(const common::RngStreams& streams, std::string_view direction,
                                 const LinkModelOptions& options)
    : options_(options),
      latency_rng_(streams.stream("linkemu/" + std::string(direction) + "/latency")),
      loss_(streams.stream("linkemu/" + std::string(direction) + "/loss"), options.gilbert_elliott),
      free_at_us_(std::numeric_limits<int64_t>::min()),
      last_delivery_us_(std::numeric_limits<int64_t>::min()) {}

int64_t LinkTransmitter::backlog_us(int64_t now_us) const {
  return free_at_us_ > now_us ? free_at_us_ - now_us : 0;
}

TransmitOutcome LinkTransmitter::transmit(int64_t ingress_us, int64_t size_bytes,
                                          const NetworkState& state) {
  TransmitOutcome out;
  out.tx_start_us = std::max(ingress_us, free_at_us_);
  const int64_t ser_us = serialization_us(size_bytes, state.throughput_mbps);
  out.tx_end_us = out.tx_start_us + ser_us;
  // A lost message was still sent: it occupies the transmitter all the same.
  free_at_us_ = out.tx_end_us;
  out.queue_ms = static_cast<double>(out.tx_start_us - ingress_us) * 1e-3;
  out.serialization_ms = static_cast<double>(ser_us) * 1e-3;
  // Draw both in every case so one term's outcome never shifts the other's numbers.
  const double latency_ms = sample_message_latency_ms(latency_rng_, state);
  out.lost = loss_.lose(std::clamp(state.loss_pct / 100.0, 0.0, 1.0));
  out.delivery_us = out.tx_end_us + std::llround(latency_ms * 1e3);
  if (!out.lost) {
    if (!options_.reordering) out.delivery_us = std::max(out.delivery_us, last_delivery_us_);
    last_delivery_us_ = std::max(last_delivery_us_, out.delivery_us);
  }
  out.latency_ms = static_cast<double>(out.delivery_us - out.tx_end_us) * 1e-3;
  return out;
}

}  // namespace a3::linkemu
