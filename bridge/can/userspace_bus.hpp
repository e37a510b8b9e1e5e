// A CAN bus between processes on one machine, for kernels without SocketCAN: every member
// carries the same 16-byte struct can_frame records as SocketCAN, over Unix-domain
// SOCK_SEQPACKET connections in a full mesh. A bus is a folder (default
// /tmp/a3rig-can-<uid>/<bus name>/); each member listens on a socket file in it and, on
// joining, connects to every member already there (joins are serialized by flock on the
// folder's lock file, so each pair of members gets exactly one connection). A frame sent is
// written to every peer's connection; a peer that is slow gets it queued (bounded), a peer
// that is gone is dropped, and a socket file left by a crashed process is removed by the next
// member that joins or leaves. The last member to leave removes the bus's folder (socket files
// of crashed members, lock file, folder); whoever started the members can do the same for a bus
// whose last member crashed (remove_userspace_can_bus_if_unused). No daemon, no hub: any member can leave or crash without stopping the
// others. Why not datagrams: a Unix datagram receiver's queue holds only
// net.unix.max_dgram_qlen (10 by default) packets, far too few for bursts of frames.
#pragma once

#include <atomic>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/can_bus.hpp"
#include "bridge/can/rx_dispatcher.hpp"

namespace a3::bridge {

struct UserspaceCanOptions {
  // Folder holding the buses ("" = default_userspace_can_root()).
  std::filesystem::path root;
  std::size_t tx_queue_frames_per_peer = 4096;  // frames waiting for a slow peer
};

// With the bus's lock: removes the socket files nobody listens on and, when no member is left,
// the lock file and the folder. True when the folder is gone; false while a member listens (or
// the folder holds files that are not the bus's). Never throws.
bool remove_userspace_can_bus_if_unused(const std::filesystem::path& directory);

class UserspaceCanBus final : public CanBus {
 public:
  // Joins (creating if needed) the bus `bus_name` (letters, digits, '-', '_', '.').
  // Throws std::runtime_error saying what failed (bad name, folder not writable, ...).
  explicit UserspaceCanBus(const std::string& bus_name, UserspaceCanOptions options = {});
  ~UserspaceCanBus() override;
  UserspaceCanBus(const UserspaceCanBus&) = delete;
  UserspaceCanBus& operator=(const UserspaceCanBus&) = delete;

  // $A3_CAN_USERSPACE_DIR, else /tmp/a3rig-can-<uid>.
  static std::filesystem::path default_root();

  std::string name() const override { return "userspace:" + bus_name_; }
  bool send(const CanFrame& frame) override;
  void start(common::Executor& executor, CanFrameHandler handler) override;
  void stop() override;
  std::size_t tx_pending() const override;
  CanBusStats stats() const override;

  // Members connected to this one right now.
  std::size_t peer_count() const;
  const std::filesystem::path& directory() const { return directory_; }
  const std::filesystem::path& socket_path() const { return socket_path_; }

 private:
  struct Peer {
    int fd = -1;
    bool dead = false;
    std::deque<std::array<uint8_t, kSocketCanFrameBytes>> backlog;
  };

  void join();
  void run();
  void stop_io_thread();
  void wake();
  void accept_peers();
  // Reads what a peer sent; false when it is gone.
  bool read_peer(Peer& peer, std::size_t& received, std::size_t& bad);
  // Writes a peer's backlog until it would block; false when the peer is gone.
  static bool drain_peer(Peer& peer);
  void remove_dead_locked();

  std::string bus_name_;
  UserspaceCanOptions options_;
  std::filesystem::path directory_;
  std::filesystem::path socket_path_;
  int listen_fd_ = -1;
  int wake_fd_ = -1;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  RxDispatcher dispatcher_;
  mutable std::mutex mutex_;  // peers and stats
  std::vector<std::unique_ptr<Peer>> peers_;
  CanBusStats stats_;
};

}  // namespace a3::bridge
