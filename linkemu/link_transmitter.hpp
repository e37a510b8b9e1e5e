// One direction of the emulated link, as a model (no bus, no clock): each message waits
// for the transmitter to finish the earlier ones (queueing), is sent at the throughput of
// n_t (serialization = size / throughput), then takes a latency sample with jitter to
// arrive; it is lost at n_t's loss rate. Without reordering, no message is delivered
// before one sent earlier in the same direction (FIFO).
#pragma once

#include <cstdint>
#include <string_view>

#include "common/rng.hpp"
#include "linkemu/loss_model.hpp"
#include "linkemu/network_state.hpp"

namespace a3::linkemu {

struct TransmitOutcome {
  bool lost = false;
  int64_t tx_start_us = 0;    // transmitter starts on it
  int64_t tx_end_us = 0;      // last bit sent
  int64_t delivery_us = 0;    // arrives (meaningless when lost)
  double queue_ms = 0.0;      // tx_start - ingress
  double serialization_ms = 0.0;
  double latency_ms = 0.0;    // delivery - tx_end: the latency sample, plus any FIFO wait
};

struct LinkModelOptions {
  bool reordering = false;
  GilbertElliottConfig gilbert_elliott;
};

// Per-message latency: lat_ms + jitter_ms · (E - 1), E ~ Exp(1): mean lat_ms, standard
// deviation jitter_ms, never below lat_ms - jitter_ms (nor 0), a right tail like queueing.
double sample_message_latency_ms(common::Rng& rng, const NetworkState& state);

// Serialization time of size_bytes at throughput_mbps, rounded up to the microsecond.
int64_t serialization_us(int64_t size_bytes, double throughput_mbps);

class LinkTransmitter {
 public:
  // Draws from the streams "linkemu/<direction>/latency" and ".../loss".
  LinkTransmitter(const common::RngStreams& streams, std::string_view direction,
                  const LinkModelOptions& options);

  TransmitOutcome transmit(int64_t ingress_us, int64_t size_bytes, const NetworkState& state);
  // How long a message arriving at now_us would wait before the transmitter is free.
  int64_t backlog_us(int64_t now_us) const;
  bool loss_in_bad_state() const { return loss_.in_bad_state(); }

 private:
  LinkModelOptions options_;
  common::Rng latency_rng_;
  LossModel loss_;
  int64_t free_at_us_;
  int64_t last_delivery_us_;
};

}  // namespace a3::linkemu
