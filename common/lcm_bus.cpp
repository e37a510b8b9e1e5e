// LCM-backed bus.
#include "common/lcm_bus.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace a3::common {

std::string resolve_lcm_url(const std::string& requested) {
  if (!requested.empty()) return requested;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && *env != '\0') {
    return env;
  }
  return kDefaultLcmUrl;
}

std::string answers_lcm_url(const std::string& url) {
  constexpr std::string_view kUdpm = "udpm://";
  constexpr int kLcmDefaultPort = 7667;  // LCM's port when a udpm URL names none
  if (url.rfind(kUdpm, 0) != 0) return url;
  const std::size_t options = std::min(url.find('?'), url.size());
  const std::size_t colon = url.rfind(':', options);
  const bool has_port = colon != std::string::npos && colon >= kUdpm.size();
  const std::string digits = has_port ? url.substr(colon + 1, options - colon - 1) : "";
  int port = kLcmDefaultPort;
  if (has_port) {
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || port <= 0 || port >= 65535) {
      throw std::invalid_argument("LCM URL '" + url + "': the port '" + digits + "' is not a number from 1 to 65534");
    }
  }
  const std::size_t group_end = has_port ? colon : options;
  return url.substr(0, group_end) + ":" + std::to_string(port + 1) + url.substr(options);
}

std::string lcm_multicast_hint() {
  return "LCM's UDP multicast needs multicast looped back on this host. As root run:\n"
         "  ip link set lo multicast on\n"
         "  ip route add 239.255.76.67/32 dev lo\n"
         "or fly in virtual time (--runtime virtual), which needs no network";
}

class LcmBus::Subscriber {
 public:
  Subscriber(LcmBus& bus, RawHandler handler) : bus_(bus), handler_(std::move(handler)) {}
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    const int64_t t_us = bus_.recv_clock_ != nullptr ? bus_.recv_clock_->now_us() : rbuf->recv_utime;
    handler_(channel, static_cast<const uint8_t*>(rbuf->data), rbuf->data_size, t_us);
  }
  lcm::Subscription* subscription = nullptr;

 private:
  LcmBus& bus_;
  RawHandler handler_;
};

LcmBus::LcmBus(const std::string& url, const Clock* recv_clock)
    : url_(resolve_lcm_url(url)), recv_clock_(recv_clock) {
  lcm_ = std::make_unique<lcm::LCM>(url_);
  if (!lcm_->good()) {
    std::string message = "cannot create LCM on '" + url_ + "'";
    if (url_.rfind("udpm://", 0) == 0) message += ".\n" + lcm_multicast_hint();
    throw std::runtime_error(message);
  }
}

LcmBus::~LcmBus() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [id, sub] : subscribers_) lcm_->unsubscribe(sub->subscription);
  subscribers_.clear();
}

bool LcmBus::publish_raw(const std::string& channel, const uint8_t* data, std::size_t size) {
  ++messages_published_;
  if (lcm_->publish(channel, data, static_cast<unsigned int>(size)) != 0) {
    ++publish_failures_;
    log_warn("bus", "LCM publish on " + channel + " failed (" + url_ + ")");
    return false;
  }
  return true;
}

SubscriptionId LcmBus::subscribe_raw(const std::string& channel, RawHandler handler) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto sub = std::make_unique<Subscriber>(*this, std::move(handler));
  // LCM channel arguments are regular expressions; quote to match the name exactly.
  std::string pattern;
  for (char c : channel) {
    if (std::string_view(".^$|()[]{}*+?\\").find(c) != std::string_view::npos) pattern += '\\';
    pattern += c;
  }
  sub->subscription = lcm_->subscribe(pattern, &Subscriber::on_message, sub.get());
  const SubscriptionId id = next_id_++;
  subscribers_.emplace(id, std::move(sub));
  return id;
}

void LcmBus::unsubscribe(SubscriptionId id) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = subscribers_.find(id);
  if (it == subscribers_.end()) return;
  lcm_->unsubscribe(it->second->subscription);
  subscribers_.erase(it);
}

int LcmBus::fileno() { return lcm_->getFileno(); }

int LcmBus::handle_ready() {
  // Bounded, so that a steady stream on one channel cannot starve the executor's timers
  // (the fd stays readable; the executor comes back for the rest).
  constexpr int kMaxMessagesPerCall = 64;
  int handled = 0;
  while (handled < kMaxMessagesPerCall && handle_one()) ++handled;
  return handled;
}

bool LcmBus::handle_one() { return lcm_->handleTimeout(0) > 0; }

bool LcmBus::handle_timeout(int timeout_ms) { return lcm_->handleTimeout(timeout_ms) > 0; }

void LcmBus::check_loopback(int timeout_ms) {
  const std::string channel = "A3_LOOPBACK_PROBE_" + std::to_string(::getpid()) + "_" +
                              std::to_string(reinterpret_cast<uintptr_t>(this));
  bool received = false;
  const SubscriptionId id =
      subscribe_raw(channel, [&](const std::string&, const uint8_t*, std::size_t, int64_t) {
        received = true;
      });
  const uint8_t probe = 1;
  const bool sent = publish_raw(channel, &probe, 1);
  for (int waited = 0; sent && !received && waited < timeout_ms; waited += 10) {
    handle_timeout(10);
  }
  unsubscribe(id);
  if (!received) {
    throw std::runtime_error("LCM on '" + url_ + "' does not deliver its own messages back. " +
                             lcm_multicast_hint());
  }
}

}  // namespace a3::common
