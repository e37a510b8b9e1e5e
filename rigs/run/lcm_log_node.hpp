// Writes every message of the rig's channels to an LCM log file (the format of lcm-logger), so
// an episode can be replayed with lcm-logplayer and inspected with lcm-spy. Event timestamps
// are the run's clock (simulated time in virtual runs).
// The log is written to "<path>.tmp-<pid>" and renamed to <path> by close() when every write
// succeeded. The first failed write (a full disk) stops the logging at once, removes the partial
// log (so that the episode, written next, has the room) and is kept in failure(); the run flies on.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/channels.hpp"
#include "common/node.hpp"

namespace a3::rigs {

// Every channel in common/channels.hpp for vehicles 0..vehicles-1, but the clock's answers and
// the node statistics.
std::vector<std::string> logged_channels(common::VehicleId vehicles);

class LcmLogNode final : public common::Node {
 public:
  // Throws common::OutputError ("<path>: <reason>") when the file cannot be created.
  explicit LcmLogNode(const std::filesystem::path& path, common::VehicleId vehicles = 1);
  ~LcmLogNode() override;
  std::string name() const override { return "lcm_log"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Subscribes every logged channel.
  std::optional<common::NodePorts> ports() const override;
  uint64_t events() const;
  // events (messages written to the log).
  const common::CounterSet& counters() const override { return counter_set_; }
  // Flushes, syncs and renames the log into place; a failure is kept in failure().
  void close();
  // "" while every write succeeded, else "<path>: <reason>" (e.g. "No space left on device").
  std::string failure() const;
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_event(const std::string& channel, const uint8_t* data, std::size_t size);
  void fail(int error_number);  // with mutex_ held

  std::filesystem::path path_;
  common::VehicleId vehicles_ = 1;
  std::filesystem::path temporary_;
  mutable std::mutex mutex_;
  std::unique_ptr<lcm::LogFile> log_;
  std::string failure_;
  common::Executor* executor_ = nullptr;
  common::CounterSet counter_set_;
  common::Counter& events_ = counter_set_.add("events");
};

}  // namespace a3::rigs
