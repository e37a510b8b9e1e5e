// LCM log writing, every write checked.
#include "rigs/core/lcm_log_node.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "common/atomic_file.hpp"
#include "common/channels.hpp"

namespace a3::rigs {

const std::vector<std::string>& rig_channels() {
  namespace ch = common::channels;
  static const std::vector<std::string> kChannels = {
      ch::kState,      ch::kActuators,  ch::kFcCommand,   ch::kFcStatus,   ch::kNet,
      ch::kLinkUpTx,   ch::kLinkUpRx,   ch::kLinkDownTx,  ch::kLinkDownRx, ch::kLinkRecord,
      ch::kEdgeRequest, ch::kEdgeReply, ch::kSliceRequest, ch::kSliceReply, ch::kPayload,
      ch::kTraffic,    ch::kEpisode,    ch::kSafety,      ch::kClock};
  return kChannels;
}

LcmLogNode::LcmLogNode(const std::filesystem::path& path) : path_(path) {
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

void LcmLogNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  for (const std::string& channel : rig_channels()) {
    bus.subscribe_raw(channel, [this](const std::string& ch, const uint8_t* data, std::size_t size, int64_t) {
      write_event(ch, data, size);
    });
  }
}

}  // namespace a3::rigs
