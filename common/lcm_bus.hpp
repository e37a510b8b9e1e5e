// The Bus over real LCM: udpm:// multicast (between threads, processes and hosts) or
// memq:// (in one process). Honours LCM_DEFAULT_URL as every LCM tool does; the default is
// udpm with ttl=0 (never leaves the host; see README "LCM networking").
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "common/bus.hpp"
#include "common/clock.hpp"

namespace a3::common {

inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

// The URL a bus uses: `requested` if not empty, else $LCM_DEFAULT_URL, else kDefaultLcmUrl.
std::string resolve_lcm_url(const std::string& requested);

// The URL lockstep followers answer the time master's grants on (GrantAcknowledger): for
// udpm://GROUP:PORT?OPTIONS the same group on the next port, where only the master listens, so
// that an answer wakes one receiver instead of every node (udpm delivers each datagram to every
// socket on its port); any other URL: the same one. Throws std::invalid_argument, naming the
// URL, when a udpm port is not a number below 65535.
std::string answers_lcm_url(const std::string& url);

// How to fix a host whose multicast loopback is not set up.
std::string lcm_multicast_hint();

class LcmBus final : public Bus {
 public:
  // Throws std::runtime_error with a fix-it message when LCM cannot be created.
  // recv_clock stamps delivered messages; nullptr: LCM's own receive timestamp.
  explicit LcmBus(const std::string& url = "", const Clock* recv_clock = nullptr);
  ~LcmBus() override;

  bool publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) override;
  SubscriptionId subscribe_raw(const std::string& channel, RawHandler handler) override;
  void unsubscribe(SubscriptionId id) override;

  // File descriptor that becomes readable when messages wait; dispatch with handle_ready().
  int fileno();
  // Dispatches the messages waiting now without blocking; returns how many.
  int handle_ready();
  // Dispatches one waiting message, if there is one, without blocking; returns whether it did.
  bool handle_one();
  // Waits up to timeout_ms for one message and dispatches it; returns false on timeout.
  bool handle_timeout(int timeout_ms);
  // Publishes a probe and waits for it to come back; throws with the multicast hint if it
  // does not (the silent failure of lcm-proj issues #60, #476, #579).
  void check_loopback(int timeout_ms = 500);

  const std::string& url() const { return url_; }
  uint64_t publish_failures() const { return publish_failures_; }
  // Messages this bus was asked to publish (from the thread that publishes).
  uint64_t messages_published() const { return messages_published_; }

 private:
  class Subscriber;
  std::string url_;
  const Clock* recv_clock_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::mutex mutex_;
  std::map<SubscriptionId, std::unique_ptr<Subscriber>> subscribers_;
  SubscriptionId next_id_ = 1;
  uint64_t publish_failures_ = 0;
  uint64_t messages_published_ = 0;
};

}  // namespace a3::common
