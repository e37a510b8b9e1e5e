// Writes every message of the rig's channels to an LCM log file (the format of lcm-logger), so
// an episode can be replayed with lcm-logplayer and inspected with lcm-spy. Event timestamps
// are the run's clock (simulated time in virtual runs).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/node.hpp"

namespace a3::rigs {

// Every channel in common/channels.hpp.
const std::vector<std::string>& rig_channels();

class LcmLogNode final : public common::Node {
 public:
  // Throws std::runtime_error when the file cannot be created.
  explicit LcmLogNode(const std::filesystem::path& path);
  ~LcmLogNode() override;
  std::string name() const override { return "lcm_log"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  uint64_t events() const;
  // events (messages written to the log).
  const common::CounterSet& counters() const override { return counter_set_; }
  void close();

 private:
  std::filesystem::path path_;
  mutable std::mutex mutex_;
  std::unique_ptr<lcm::LogFile> log_;
  common::Executor* executor_ = nullptr;
  common::CounterSet counter_set_;
  common::Counter& events_ = counter_set_.add("events");
};

}  // namespace a3::rigs
