// Real-time node threads.
#include "common/runtime.hpp"

#include <exception>

namespace a3::common {

RealTimeNodeThread::RealTimeNodeThread(Node& node, const WallClock& clock,
                                       const std::string& lcm_url)
    : node_(node), bus_(lcm_url, &clock), executor_(clock, &bus_) {}

RealTimeNodeThread::~RealTimeNodeThread() { stop_and_join(); }

void RealTimeNodeThread::start() {
  node_.start(executor_, bus_);
  thread_ = std::thread([this] {
    try {
      executor_.run();
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(failure_mutex_);
      failure_ = e.what();
      log_error(node_.name(), std::string("stopped: ") + e.what());
    }
  });
}

void RealTimeNodeThread::stop_and_join() {
  executor_.stop();
  if (thread_.joinable()) thread_.join();
}

std::string RealTimeNodeThread::failure() const {
  std::lock_guard<std::mutex> lock(failure_mutex_);
  return failure_;
}

}  // namespace a3::common
