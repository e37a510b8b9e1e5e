// SocketCAN transport (see socketcan_bus.hpp).
#include "bridge/can/socketcan_bus.hpp"

#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

namespace a3::bridge {
namespace {

std::string errno_text(int error) { return std::strerror(error); }

// Opens a bound raw CAN socket, or returns -1 with the reason.
void enlarge_receive_buffer(int fd, int bytes) {
  if (bytes <= 0) return;
  if (::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &bytes, sizeof bytes) != 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);  // capped by rmem_max
  }
}

int open_can_socket(const std::string& interface, bool own_frames, std::string& why) {
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    why = "'" + interface + "' is not a valid interface name";
    return -1;
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    why = "this kernel has no SocketCAN (socket(AF_CAN): " + errno_text(errno) + ")";
    return -1;
  }
  struct ifreq ifr {};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
    why = "no network interface named " + interface +
          " (for a virtual one, as root: modprobe vcan; ip link add dev " + interface +
          " type vcan; ip link set up " + interface + ")";
    ::close(fd);
    return -1;
  }
  struct ifreq flags {};
  std::strncpy(flags.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFFLAGS, &flags) == 0 && (flags.ifr_flags & IFF_UP) == 0) {
    why = interface + " is down (ip link set up " + interface + ")";
    ::close(fd);
    return -1;
  }
  const int own = own_frames ? 1 : 0;
  ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof own);
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);  // drop counter per message
  struct sockaddr_can addr {};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<struct sockaddr*>(&addr), sizeof addr) < 0) {
    why = "cannot bind a CAN socket to " + interface + " (" + errno_text(errno) +
          "; is it a CAN interface?)";
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

std::string SocketCanBus::probe(const std::string& interface) {
  std::string why;
  const int fd = open_can_socket(interface, false, why);
  if (fd >= 0) ::close(fd);
  return why;
}

SocketCanBus::SocketCanBus(const std::string& interface, SocketCanOptions options)
    : interface_(interface), options_(options) {
  std::string why;
  socket_fd_ = open_can_socket(interface, options.receive_own_frames, why);
  if (socket_fd_ < 0) throw std::runtime_error("SocketCAN " + interface + ": " + why);
  enlarge_receive_buffer(socket_fd_, options.receive_buffer_bytes);
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) {
    ::close(socket_fd_);
    throw std::runtime_error("SocketCAN " + interface + ": eventfd: " + errno_text(errno));
  }
  // The I/O thread runs from the start: it drains the transmit queue even before start().
  thread_ = std::thread([this] { run(); });
}

SocketCanBus::~SocketCanBus() {
  stop();
  stop_io_thread();
  if (socket_fd_ >= 0) ::close(socket_fd_);
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

int SocketCanBus::write_frame(const CanFrame& frame) {
  struct can_frame raw;
  to_socketcan(frame, raw);
  const ssize_t n = ::write(socket_fd_, &raw, sizeof raw);
  if (n == static_cast<ssize_t>(sizeof raw)) return 0;
  return n < 0 ? errno : EIO;
}

bool SocketCanBus::send(const CanFrame& frame) {
  std::lock_guard lock(mutex_);
  if (tx_queue_.empty()) {
    const int error = write_frame(frame);
    if (error == 0) {
      ++stats_.frames_sent;
      return true;
    }
    if (error != EAGAIN && error != ENOBUFS) {
      ++stats_.send_refused;
      return false;
    }
  }
  if (tx_queue_.size() >= options_.tx_queue_frames) {
    ++stats_.send_refused;
    return false;
  }
  tx_queue_.push_back(frame);
  ++stats_.frames_sent;
  stats_.tx_queue_peak = std::max(stats_.tx_queue_peak, tx_queue_.size());
  wake();
  return true;
}

int SocketCanBus::drain_locked() {
  while (!tx_queue_.empty()) {
    const int error = write_frame(tx_queue_.front());
    if (error == EAGAIN || error == ENOBUFS) return error;
    if (error != 0) ++stats_.send_refused;  // counted as sent before; the interface refused it
    tx_queue_.pop_front();
  }
  return 0;
}

void SocketCanBus::wake() {
  const uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
}

void SocketCanBus::start(common::Executor& executor, CanFrameHandler handler) {
  if (dispatcher_.started()) throw std::logic_error(name() + ": started twice");
  dispatcher_.start(executor, std::move(handler));
}

void SocketCanBus::stop() { dispatcher_.stop(); }

void SocketCanBus::stop_io_thread() {
  if (!thread_.joinable()) return;
  stop_ = true;
  wake();
  thread_.join();
}

void SocketCanBus::run() {
  int last_tx_error = 0;
  while (!stop_) {
    bool want_write;
    {
      std::lock_guard lock(mutex_);
      want_write = !tx_queue_.empty();
    }
    struct pollfd fds[2] = {{socket_fd_, static_cast<short>(POLLIN | (want_write ? POLLOUT : 0)), 0},
                            {wake_fd_, POLLIN, 0}};
    // ENOBUFS does not make the socket unwritable, so POLLOUT would spin: retry in 1 ms.
    const int timeout_ms = want_write && last_tx_error == ENOBUFS ? 1 : -1;
    const int ready = ::poll(fds, 2, timeout_ms);
    if (ready < 0 && errno != EINTR) break;
    if (fds[1].revents & POLLIN) {
      uint64_t count;
      [[maybe_unused]] const ssize_t n = ::read(wake_fd_, &count, sizeof count);
    }
    if (want_write) {
      std::lock_guard lock(mutex_);
      last_tx_error = drain_locked();
    }
    if (fds[0].revents & POLLIN) {
      const int64_t rx_time_us = dispatcher_.now_us();
      std::size_t received = 0;
      std::size_t bad = 0;
      uint32_t drops = kernel_drops_;
      for (int i = 0; i < 256; ++i) {
        struct can_frame raw;
        struct iovec iov {&raw, sizeof raw};
        alignas(struct cmsghdr) char control[CMSG_SPACE(sizeof(uint32_t))];
        struct msghdr msg {};
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        msg.msg_control = control;
        msg.msg_controllen = sizeof control;
        const ssize_t n = ::recvmsg(socket_fd_, &msg, MSG_DONTWAIT);
        if (n < 0) break;
        for (struct cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
          if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
            std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
          }
        }
        const auto frame = n == static_cast<ssize_t>(sizeof raw) ? from_socketcan(raw) : std::nullopt;
        if (!frame) {
          ++bad;
          continue;
        }
        dispatcher_.push(*frame, rx_time_us);
        ++received;
      }
      received = dispatcher_.flush();
      std::lock_guard lock(mutex_);
      stats_.frames_received += received;
      stats_.receive_errors += bad;
      stats_.receive_overruns += static_cast<uint32_t>(drops - kernel_drops_);
      kernel_drops_ = drops;
    }
  }
}

std::size_t SocketCanBus::tx_pending() const {
  std::lock_guard lock(mutex_);
  return tx_queue_.size();
}

CanBusStats SocketCanBus::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace a3::bridge
