// The message bus every node talks through: raw LCM-encoded bytes on named channels,
// with typed helpers for lcm-gen types. Implementations: LcmBus (real LCM: udpm://, memq://)
// and VirtualBus (in-process, delivered by the virtual-time scheduler). A message that
// fails to decode is counted and logged, never passed on (see decode_failures()).
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/log.hpp"

namespace a3::common {

using SubscriptionId = uint64_t;

// Handler for raw bytes; recv_utime_us is the receiver's clock at delivery.
using RawHandler =
    std::function<void(const std::string& channel, const uint8_t* data, std::size_t size,
                       int64_t recv_utime_us)>;

class Bus {
 public:
  virtual ~Bus() = default;
  // Publishes already-encoded bytes. Returns false (and logs) when the transport refused.
  virtual bool publish_raw(const std::string& channel, const uint8_t* data,
                           std::size_t size) = 0;
  virtual SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) = 0;
  virtual void unsubscribe(SubscriptionId id) = 0;

  // Encodes an lcm-gen message and publishes it.
  template <typename Msg>
  bool publish(const std::string& channel, const Msg& msg) {
    const int size = msg.getEncodedSize();
    std::vector<uint8_t> buffer(static_cast<std::size_t>(size));
    if (msg.encode(buffer.data(), 0, size) != size) {
      log_error("bus", "cannot encode " + std::string(Msg::getTypeName()) + " for " + channel);
      return false;
    }
    return publish_raw(channel, buffer.data(), buffer.size());
  }

  // Subscribes with decoding; a message that does not decode as Msg is dropped and counted.
  template <typename Msg>
  SubscriptionId subscribe(const std::string& channel,
                           std::function<void(const Msg& msg, int64_t recv_utime_us)> handler) {
    return subscribe_raw(channel, [this, handler = std::move(handler)](
                                      const std::string& ch, const uint8_t* data,
                                      std::size_t size, int64_t recv_utime_us) {
      Msg msg;
      int decoded = -1;
      try {
        decoded = msg.decode(data, 0, static_cast<int>(size));
      } catch (const std::exception&) {
        // lcm-gen decoders throw (length_error, bad_alloc) on a bad length field.
        decoded = -1;
      }
      if (decoded < 0) {
        ++decode_failures_;
        log_warn("bus", "dropped a message on " + ch + " that does not decode as " +
                            std::string(Msg::getTypeName()) + " (" + std::to_string(size) +
                            " bytes)");
        return;
      }
      handler(msg, recv_utime_us);
    });
  }

  uint64_t decode_failures() const { return decode_failures_.load(); }

 protected:
  std::atomic<uint64_t> decode_failures_{0};
};

}  // namespace a3::common
