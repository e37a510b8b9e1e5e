// Command sources and the rate limit of refusal reports.
#include "bridge/nodes/command_sources.hpp"

#include <algorithm>
#include <stdexcept>

namespace a3::bridge {

void check_command_sources(const std::vector<uint8_t>& sources, uint8_t own_node_id) {
  if (sources.empty()) {
    throw std::invalid_argument("fc node: command sources: none given; the vehicle could not be commanded at all");
  }
  for (const uint8_t id : sources) {
    if (id < 1 || id > 127) {
      throw std::invalid_argument("fc node: command source " + std::to_string(id) + " is not a node ID (1..127)");
    }
    if (id == own_node_id) {
      throw std::invalid_argument("fc node: command source " + std::to_string(id) + " is the fc's own node ID");
    }
  }
}

bool is_command_source(const std::vector<uint8_t>& sources, uint8_t node_id) {
  return std::find(sources.begin(), sources.end(), node_id) != sources.end();
}

std::string command_sources_text(const std::vector<uint8_t>& sources) {
  std::string text;
  for (const uint8_t id : sources) text += (text.empty() ? "" : ", ") + std::to_string(id);
  return text;
}

RefusalReports::RefusalReports(int64_t interval_us, Report report)
    : interval_us_(interval_us), report_(std::move(report)) {
  if (interval_us <= 0) {
    throw std::invalid_argument("refusal report interval must be positive, got " + std::to_string(interval_us) + " us");
  }
}

void RefusalReports::stop() {
  if (scheduled_ && executor_ != nullptr) executor_->cancel(timer_);
  scheduled_ = false;
}

void RefusalReports::record() {
  if (executor_ == nullptr) throw std::logic_error("refusal reports: record() before start()");
  ++total_;
  ++waiting_;
  if (scheduled_) return;  // the report on its way covers this refusal too
  scheduled_ = true;
  timer_ = executor_->schedule_at(std::max(executor_->clock().now_us(), next_report_us_), [this] { report(); });
}

void RefusalReports::report() {
  scheduled_ = false;
  const uint64_t covered = waiting_;
  waiting_ = 0;
  next_report_us_ = executor_->clock().now_us() + interval_us_;
  if (covered > 0) report_(covered, total_);
}

}  // namespace a3::bridge
