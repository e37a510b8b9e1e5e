// LCM log writing.
#include "rigs/core/lcm_log_node.hpp"

#include <stdexcept>

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
  log_ = std::make_unique<lcm::LogFile>(path.string(), "w");
  if (!log_->good()) throw std::runtime_error(path.string() + ": cannot create the LCM log");
}

LcmLogNode::~LcmLogNode() { close(); }

void LcmLogNode::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  log_.reset();
}

uint64_t LcmLogNode::events() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return events_;
}

void LcmLogNode::start(common::Executor& executor, common::Bus& bus) {
  executor_ = &executor;
  for (const std::string& channel : rig_channels()) {
    bus.subscribe_raw(channel, [this](const std::string& ch, const uint8_t* data, std::size_t size, int64_t) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!log_) return;
      lcm::LogEvent ev;
      ev.eventnum = static_cast<int64_t>(events_.add() - 1);
      ev.timestamp = executor_->clock().now_us();
      ev.channel = ch;
      ev.datalen = static_cast<int32_t>(size);
      ev.data = const_cast<uint8_t*>(data);
      log_->writeEvent(&ev);
    });
  }
}

}  // namespace a3::rigs
