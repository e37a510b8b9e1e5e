// LCM log writing, every write checked.
#include "rigs/run/lcm_log_node.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "common/atomic_file.hpp"
#include "common/channels.hpp"

namespace a3::rigs {

std::vector<std::string> logged_channels(common::VehicleId vehicles) {
  std::vector<std::string> names;
  for (common::VehicleId v = 0; v < vehicles; ++v) {
    for (const auto& c : common::channels::declared_channels(v)) {
      // The clock's answers travel on a bus of their own; the statistics are in the episode.
      if (c.per_vehicle || v == 0) {
        if (c.name != common::channels::kClockAck.name && c.name != common::channels::kNodeStats.name) {
          names.push_back(c.name);
        }
      }
    }
  }
  return names;
}

LcmLogNode::LcmLogNode(const std::filesystem::path& path, common::VehicleId vehicles) : path_(path), vehicles_(vehicles) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) throw common::OutputError(path.parent_path().string() + ": cannot create the folder: " + ec.message());
  temporary_ = path;
  temporary_ += ".tmp-" + std::to_string(::getpid());
  errno = 0;
  log_ = std::make_unique<lcm::LogFile>(temporary_.string(), "w");
  if (!log_->good()) {
    throw common::OutputError(path.string() + ": cannot create the LCM log: " + std::strerror(errno ? errno : EIO));
  }
}

LcmLogNode::~LcmLogNode() {
  close();
}

void LcmLogNode::fail(int error_number) {
  failure_ = path_.string() + ": " + std::strerror(error_number);
  log_.reset();
  ::unlink(temporary_.c_str());
}

void LcmLogNode::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!log_) return;
  std::FILE* file = log_->getFilePtr();
  if (std::fflush(file) != 0 || ::fsync(::fileno(file)) != 0) return fail(errno);
  log_.reset();  // fclose: everything was flushed above
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail(errno);
}

std::string LcmLogNode::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

uint64_t LcmLogNode::events() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return events_;
}

void LcmLogNode::write_event(const std::string& channel, const uint8_t* data, std::size_t size) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!log_) return;
  lcm::LogEvent ev;
  ev.eventnum = static_cast<int64_t>(events_);
  ev.timestamp = executor_->clock().now_us();
  ev.channel = channel;
  ev.datalen = static_cast<int32_t>(size);
  ev.data = const_cast<uint8_t*>(data);
  errno = 0;
  // Flushed per event: a full disk is noticed at the message it cut, not when the buffer fills.
  if (log_->writeEvent(&ev) != 0 || std::fflush(log_->getFilePtr()) != 0) return fail(errno ? errno : EIO);
  events_.add();
}

std::optional<common::NodePorts> LcmLogNode::ports() const {
  common::NodePorts ports;
  for (common::VehicleId v = 0; v < vehicles_; ++v) {
    for (const auto& c : common::channels::declared_channels(v)) {
      ports.declare(c.name, c.message_type, common::Port::Direction::kSubscribe);
    }
  }
  return ports;
}

void LcmLogNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  for (const std::string& channel : logged_channels(vehicles_)) {
    bus.subscribe_raw(channel, [this](const std::string& ch, const uint8_t* data, std::size_t size, int64_t) {
      write_event(ch, data, size);
    });
  }
}

}  // namespace a3::rigs
