// The message bus every node talks through: raw LCM-encoded bytes on named channels,
// with typed helpers for lcm-gen types. Implementations: LcmBus (real LCM: udpm://, memq://)
// and VirtualBus (in-process, delivered by the virtual-time scheduler). A message that
// fails to decode is counted and logged, never passed on (see decode_failures()).
// Typed publish encodes into a reused per-thread buffer; typed subscribers of one type that
// receive the same bytes one after another share one decode (decoding is deterministic).
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "common/channel.hpp"
#include "common/log.hpp"

namespace a3::common {

namespace bus_detail {

// Per-thread encode buffers, one per nesting level of typed publish (a handler may publish
// while its own publisher's bytes are still being delivered synchronously).
struct EncodeBuffers {
  std::vector<std::vector<uint8_t>> levels;
  std::size_t depth = 0;
};
// Function-local: GCC 12 does not reliably initialise namespace-scope thread_local templates.
inline EncodeBuffers& encode_buffers() {
  thread_local EncodeBuffers buffers;
  return buffers;
}

// Takes this thread's next free buffer, of at least `size` bytes, for its lifetime.
class EncodeBuffer {
 public:
  explicit EncodeBuffer(std::size_t size) {
    EncodeBuffers& buffers = encode_buffers();
    if (buffers.depth == buffers.levels.size()) buffers.levels.emplace_back();
    std::vector<uint8_t>& level = buffers.levels[buffers.depth++];
    if (level.size() < size) level.resize(size);
    data_ = level.data();  // stable: only this level's owner resizes it
  }
  ~EncodeBuffer() { --encode_buffers().depth; }
  EncodeBuffer(const EncodeBuffer&) = delete;
  EncodeBuffer& operator=(const EncodeBuffer&) = delete;
  uint8_t* data() const { return data_; }

 private:
  uint8_t* data_ = nullptr;
};

// The last message of type Msg this thread decoded and the bytes it came from. In use while
// a handler holds it; a nested delivery then decodes on its own.
template <typename Msg>
struct DecodeCache {
  Msg msg;
  std::vector<uint8_t> bytes;
  bool valid = false;
  bool in_use = false;

  bool holds(const uint8_t* data, std::size_t size) const {
    return valid && bytes.size() == size && (size == 0 || std::memcmp(bytes.data(), data, size) == 0);
  }
};
template <typename Msg>
DecodeCache<Msg>& decode_cache() {
  thread_local DecodeCache<Msg> cache;
  return cache;
}

// Decodes into msg (reset first, as a fresh message); false when the bytes are not a Msg.
template <typename Msg>
bool decode_message(Msg& msg, const uint8_t* data, std::size_t size) {
  msg = Msg();
  try {
    return msg.decode(data, 0, static_cast<int>(size)) >= 0;
  } catch (const std::exception&) {
    // lcm-gen decoders throw (length_error, bad_alloc) on a bad length field.
    return false;
  }
}

}  // namespace bus_detail

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
    const bus_detail::EncodeBuffer buffer(static_cast<std::size_t>(size));
    if (msg.encode(buffer.data(), 0, size) != size) {
      log_error("bus", "cannot encode " + std::string(Msg::getTypeName()) + " for " + channel);
      return false;
    }
    return publish_raw(channel, buffer.data(), static_cast<std::size_t>(size));
  }

  // The same on a declared channel (channels.hpp), whose type the message must have.
  template <typename Msg>
  bool publish(const TypedChannel<Msg>& channel, const std::type_identity_t<Msg>& msg) {
    return publish(channel.name, msg);
  }
  template <typename Msg>
  bool publish(const RigChannel<Msg>& channel, const std::type_identity_t<Msg>& msg) {
    return publish(std::string(channel.name), msg);
  }

  // Subscribes with decoding; a message that does not decode as Msg is dropped and counted.
  template <typename Msg>
  SubscriptionId subscribe(const TypedChannel<Msg>& channel,
                           std::type_identity_t<std::function<void(const Msg& msg, int64_t recv_utime_us)>> handler) {
    return subscribe<Msg>(channel.name, std::move(handler));
  }
  template <typename Msg>
  SubscriptionId subscribe(const RigChannel<Msg>& channel,
                           std::type_identity_t<std::function<void(const Msg& msg, int64_t recv_utime_us)>> handler) {
    return subscribe<Msg>(std::string(channel.name), std::move(handler));
  }
  template <typename Msg>
  SubscriptionId subscribe(const std::string& channel,
                           std::function<void(const Msg& msg, int64_t recv_utime_us)> handler) {
    return subscribe_raw(channel, [this, handler = std::move(handler)](
                                      const std::string& ch, const uint8_t* data,
                                      std::size_t size, int64_t recv_utime_us) {
      bus_detail::DecodeCache<Msg>& cache = bus_detail::decode_cache<Msg>();
      if (cache.in_use) {
        // Delivered from inside another handler of this type: that one still reads the cache.
        Msg msg;
        if (!bus_detail::decode_message(msg, data, size)) return count_decode_failure<Msg>(ch, size);
        handler(msg, recv_utime_us);
        return;
      }
      if (!cache.holds(data, size)) {
        cache.valid = bus_detail::decode_message(cache.msg, data, size);
        if (!cache.valid) return count_decode_failure<Msg>(ch, size);
        cache.bytes.assign(data, data + size);
      }
      cache.in_use = true;
      struct Release {
        bool& in_use;
        ~Release() { in_use = false; }
      } release{cache.in_use};
      handler(cache.msg, recv_utime_us);
    });
  }

  uint64_t decode_failures() const { return decode_failures_.load(); }
  // Where decode failures are counted: this bus, or the one a wrapper forwards to.
  virtual Bus& counting_bus() { return *this; }

 protected:
  template <typename Msg>
  void count_decode_failure(const std::string& channel, std::size_t size) {
    ++counting_bus().decode_failures_;
    log_warn("bus", "dropped a message on " + channel + " that does not decode as " +
                        std::string(Msg::getTypeName()) + " (" + std::to_string(size) + " bytes)");
  }

  std::atomic<uint64_t> decode_failures_{0};
};

}  // namespace a3::common
