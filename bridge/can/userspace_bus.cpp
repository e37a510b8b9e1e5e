// Userspace CAN bus over a mesh of Unix SOCK_SEQPACKET connections (see userspace_bus.hpp).
#include "bridge/can/userspace_bus.hpp"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace a3::bridge {
namespace {

std::string errno_text(int error) { return std::strerror(error); }

bool valid_bus_name(const std::string& name) {
  if (name.empty() || name.size() > 32 || name == "." || name == "..") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

bool make_address(const std::filesystem::path& path, struct sockaddr_un& addr) {
  const std::string text = path.string();
  if (text.size() >= sizeof addr.sun_path) return false;
  std::memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, text.c_str(), text.size() + 1);
  return true;
}

// Connects to a member's socket; -1 when nobody listens there any more.
int connect_member(const std::filesystem::path& path) {
  struct sockaddr_un addr;
  if (!make_address(path, addr)) return -1;
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  if (::connect(fd, reinterpret_cast<struct sockaddr*>(&addr), sizeof addr) < 0) {
    ::close(fd);
    return -1;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return fd;
}

void tune_peer_socket(int fd) {
  // Room for bursts in the kernel before frames wait in the peer's backlog.
  const int bytes = 1 << 20;
  ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof bytes);
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
}

// The bus's lock file, opened and locked; -1 with errno set when it cannot be had. A lock file
// removed (with its folder) by the last member leaving while we waited for it is not the bus's
// any more: that attempt fails with ESTALE, and the caller tries again.
int lock_bus_folder(const std::filesystem::path& lock_path, bool create) {
  const int fd = ::open(lock_path.c_str(), O_RDWR | O_CLOEXEC | (create ? O_CREAT : 0), 0600);
  if (fd < 0) return -1;
  ::flock(fd, LOCK_EX);
  struct stat held {}, on_disk {};
  if (::fstat(fd, &held) != 0 || ::stat(lock_path.c_str(), &on_disk) != 0 || held.st_ino != on_disk.st_ino ||
      held.st_dev != on_disk.st_dev) {
    ::close(fd);
    errno = ESTALE;
    return -1;
  }
  return fd;
}

void unlock_bus_folder(int lock_fd) {
  ::flock(lock_fd, LOCK_UN);
  ::close(lock_fd);
}

// With the bus's lock held: removes the socket files nobody listens on; true when a member is
// still there.
bool remove_stale_members(const std::filesystem::path& directory) {
  bool members = false;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    if (entry.path().extension() != ".sock") continue;
    const int fd = connect_member(entry.path());
    if (fd < 0) {
      ::unlink(entry.path().c_str());
      continue;
    }
    ::close(fd);
    members = true;
  }
  return members;
}

}  // namespace

bool remove_userspace_can_bus_if_unused(const std::filesystem::path& directory) {
  const std::filesystem::path lock_path = directory / ".lock";
  const int lock_fd = lock_bus_folder(lock_path, false);
  if (lock_fd < 0) {
    // No lock file: the folder is gone, or holds nothing of a bus (a crash before the first join).
    ::rmdir(directory.c_str());
    return !std::filesystem::exists(directory);
  }
  bool removed = false;
  if (!remove_stale_members(directory)) {
    ::unlink(lock_path.c_str());
    removed = ::rmdir(directory.c_str()) == 0;  // fails, leaving the folder, if it holds anything else
  }
  unlock_bus_folder(lock_fd);
  return removed;
}

std::filesystem::path UserspaceCanBus::default_root() {
  if (const char* env = std::getenv("A3_CAN_USERSPACE_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return "/tmp/a3rig-can-" + std::to_string(::getuid());
}

UserspaceCanBus::UserspaceCanBus(const std::string& bus_name, UserspaceCanOptions options)
    : bus_name_(bus_name), options_(std::move(options)) {
  if (!valid_bus_name(bus_name)) {
    throw std::runtime_error("userspace CAN bus name '" + bus_name +
                             "' must be 1-32 letters, digits, '-', '_' or '.'");
  }
  const std::filesystem::path root = options_.root.empty() ? default_root() : options_.root;
  directory_ = root / bus_name;
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::runtime_error("userspace CAN bus: eventfd: " + errno_text(errno));
  try {
    join();
  } catch (...) {
    ::close(wake_fd_);
    throw;
  }
  // The I/O thread runs from the start: it accepts members that join later and drains the
  // peers' queues even before start().
  thread_ = std::thread([this] { run(); });
}

void UserspaceCanBus::join() {
  const std::filesystem::path lock_path = directory_ / ".lock";
  int lock_fd = -1;
  // A leaving last member may remove the folder between our steps: then start over.
  for (int attempt = 0; attempt < 100 && lock_fd < 0; ++attempt) {
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec) {
      throw std::runtime_error("userspace CAN bus: cannot create " + directory_.string() + ": " + ec.message());
    }
    lock_fd = lock_bus_folder(lock_path, true);
    if (lock_fd < 0 && errno != ENOENT && errno != ESTALE) {
      throw std::runtime_error("userspace CAN bus: cannot open " + lock_path.string() + ": " + errno_text(errno));
    }
  }
  if (lock_fd < 0) {
    throw std::runtime_error("userspace CAN bus: " + directory_.string() +
                             " kept disappearing while joining (100 attempts)");
  }
  struct Unlock {
    int fd;
    ~Unlock() { unlock_bus_folder(fd); }
  } unlock{lock_fd};

  static std::atomic<unsigned> counter{0};
  socket_path_ = directory_ / (std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".sock");
  struct sockaddr_un addr;
  if (!make_address(socket_path_, addr)) {
    throw std::runtime_error("userspace CAN bus: socket path too long for a Unix socket: " +
                             socket_path_.string() + " (set A3_CAN_USERSPACE_DIR to a shorter folder)");
  }
  ::unlink(socket_path_.c_str());
  listen_fd_ = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0 || ::bind(listen_fd_, reinterpret_cast<struct sockaddr*>(&addr), sizeof addr) < 0 ||
      ::listen(listen_fd_, 128) < 0) {
    const std::string why = errno_text(errno);
    if (listen_fd_ >= 0) ::close(listen_fd_);
    throw std::runtime_error("userspace CAN bus: cannot listen on " + socket_path_.string() + ": " + why);
  }
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory_, ec)) {
    if (entry.path().extension() != ".sock" || entry.path() == socket_path_) continue;
    const int fd = connect_member(entry.path());
    if (fd < 0) {
      ::unlink(entry.path().c_str());  // left behind by a member that is gone
      continue;
    }
    tune_peer_socket(fd);
    auto peer = std::make_unique<Peer>();
    peer->fd = fd;
    peers_.push_back(std::move(peer));
  }
}

UserspaceCanBus::~UserspaceCanBus() {
  stop();
  stop_io_thread();
  for (auto& peer : peers_) ::close(peer->fd);
  if (listen_fd_ >= 0) ::close(listen_fd_);
  ::unlink(socket_path_.c_str());
  if (wake_fd_ >= 0) ::close(wake_fd_);
  remove_userspace_can_bus_if_unused(directory_);  // the last member out removes the bus's folder
}

bool UserspaceCanBus::send(const CanFrame& frame) {
  std::array<uint8_t, kSocketCanFrameBytes> record;
  to_socketcan_bytes(frame, record.data());
  std::lock_guard lock(mutex_);
  bool all_taken = true;
  bool queued = false;
  for (auto& peer : peers_) {
    if (peer->dead) continue;
    if (peer->backlog.empty()) {
      const ssize_t n = ::send(peer->fd, record.data(), record.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n == static_cast<ssize_t>(record.size())) continue;
      if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
        peer->dead = true;
        continue;
      }
    }
    if (peer->backlog.size() >= options_.tx_queue_frames_per_peer) {
      ++stats_.peer_overruns;
      all_taken = false;
      continue;
    }
    peer->backlog.push_back(record);
    stats_.tx_queue_peak = std::max(stats_.tx_queue_peak, peer->backlog.size());
    queued = true;
  }
  if (queued) wake();
  if (!all_taken) {
    ++stats_.send_refused;
    return false;
  }
  ++stats_.frames_sent;
  return true;
}

void UserspaceCanBus::wake() {
  const uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
}

void UserspaceCanBus::start(common::Executor& executor, CanFrameHandler handler) {
  if (dispatcher_.started()) throw std::logic_error(name() + ": started twice");
  dispatcher_.start(executor, std::move(handler));
}

void UserspaceCanBus::stop() { dispatcher_.stop(); }

void UserspaceCanBus::stop_io_thread() {
  if (!thread_.joinable()) return;
  stop_ = true;
  wake();
  thread_.join();
}

void UserspaceCanBus::accept_peers() {
  while (true) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;
    tune_peer_socket(fd);
    auto peer = std::make_unique<Peer>();
    peer->fd = fd;
    std::lock_guard lock(mutex_);
    peers_.push_back(std::move(peer));
  }
}

bool UserspaceCanBus::read_peer(Peer& peer, std::size_t& received, std::size_t& bad) {
  const int64_t rx_time_us = dispatcher_.now_us();
  for (int i = 0; i < 256; ++i) {
    uint8_t record[kSocketCanFrameBytes + 1];
    const ssize_t n = ::recv(peer.fd, record, sizeof record, MSG_DONTWAIT);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    const auto frame = from_socketcan_bytes(record, static_cast<std::size_t>(n));
    if (!frame) {
      ++bad;
      continue;
    }
    dispatcher_.push(*frame, rx_time_us);
    ++received;
  }
  return true;
}

bool UserspaceCanBus::drain_peer(Peer& peer) {
  while (!peer.backlog.empty()) {
    const auto& record = peer.backlog.front();
    const ssize_t n = ::send(peer.fd, record.data(), record.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK;
    peer.backlog.pop_front();
  }
  return true;
}

void UserspaceCanBus::remove_dead_locked() {
  for (auto& peer : peers_) {
    if (peer->dead) ::close(peer->fd);
  }
  peers_.erase(std::remove_if(peers_.begin(), peers_.end(), [](const auto& p) { return p->dead; }),
               peers_.end());
}

void UserspaceCanBus::run() {
  std::vector<struct pollfd> fds;
  std::vector<Peer*> polled;
  while (!stop_) {
    fds.clear();
    polled.clear();
    fds.push_back({wake_fd_, POLLIN, 0});
    fds.push_back({listen_fd_, POLLIN, 0});
    {
      std::lock_guard lock(mutex_);
      remove_dead_locked();
      for (auto& peer : peers_) {
        const short events = static_cast<short>(POLLIN | (peer->backlog.empty() ? 0 : POLLOUT));
        fds.push_back({peer->fd, events, 0});
        polled.push_back(peer.get());
      }
    }
    if (::poll(fds.data(), fds.size(), -1) < 0 && errno != EINTR) break;
    if (fds[0].revents & POLLIN) {
      uint64_t count;
      [[maybe_unused]] const ssize_t n = ::read(wake_fd_, &count, sizeof count);
    }
    if (fds[1].revents & POLLIN) accept_peers();
    std::size_t received = 0;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < polled.size(); ++i) {
      Peer& peer = *polled[i];
      const short revents = fds[i + 2].revents;
      bool alive = true;
      if (revents & (POLLIN | POLLHUP | POLLERR)) alive = read_peer(peer, received, bad);
      std::lock_guard lock(mutex_);
      if (alive && !peer.backlog.empty()) alive = drain_peer(peer);
      if (!alive) peer.dead = true;
    }
    received = dispatcher_.flush();
    std::lock_guard lock(mutex_);
    stats_.frames_received += received;
    stats_.receive_errors += bad;
  }
}

std::size_t UserspaceCanBus::tx_pending() const {
  std::lock_guard lock(mutex_);
  std::size_t pending = 0;
  for (const auto& peer : peers_) pending = std::max(pending, peer->backlog.size());
  return pending;
}

std::size_t UserspaceCanBus::peer_count() const {
  std::lock_guard lock(mutex_);
  return static_cast<std::size_t>(
      std::count_if(peers_.begin(), peers_.end(), [](const auto& p) { return !p->dead; }));
}

CanBusStats UserspaceCanBus::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace a3::bridge
