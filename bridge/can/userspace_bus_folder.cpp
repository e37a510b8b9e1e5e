// Cleaning up userspace CAN bus folders after runs.
#include "bridge/can/userspace_bus_folder.hpp"

#include <errno.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <system_error>

#include "bridge/can/can_bus_factory.hpp"
#include "common/log.hpp"

namespace a3::bridge {
namespace {

// The pid in "<prefix><pid>", or 0 when the name is not of that form.
pid_t pid_of(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string digits = name.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return 0;
  return static_cast<pid_t>(std::atol(digits.c_str()));
}

bool process_is_gone(pid_t pid) { return ::kill(pid, 0) != 0 && errno == ESRCH; }

}  // namespace

std::size_t remove_userspace_buses_of_dead_runs(const std::filesystem::path& root, const std::string& prefix) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(root, ec)) {
    const pid_t pid = pid_of(entry.path().filename().string(), prefix);
    if (pid <= 0 || !process_is_gone(pid)) continue;
    removed += remove_userspace_can_bus_if_unused(entry.path()) ? 1 : 0;
  }
  return removed;
}

UserspaceBusFolderGuard::UserspaceBusFolderGuard(const std::string& can_spec, const UserspaceCanOptions& options) {
  try {
    const CanTransportChoice choice = choose_can_transport(can_spec);
    if (choice.transport != CanTransport::kUserspace) return;
    const std::filesystem::path root = options.root.empty() ? UserspaceCanBus::default_root() : options.root;
    directory_ = root / choice.name;
    // A bus named after this process (<prefix><pid>) is a per-run bus: the folders of earlier
    // runs whose process is gone (killed before anyone could leave) go too.
    const std::string own_pid = std::to_string(::getpid());
    if (choice.name.size() > own_pid.size() &&
        choice.name.compare(choice.name.size() - own_pid.size(), own_pid.size(), own_pid) == 0) {
      remove_userspace_buses_of_dead_runs(root, choice.name.substr(0, choice.name.size() - own_pid.size()));
    }
  } catch (const std::exception&) {
    directory_.clear();  // not a bus spec at all: opening it will say why
  }
}

UserspaceBusFolderGuard::~UserspaceBusFolderGuard() {
  if (directory_.empty() || remove_userspace_can_bus_if_unused(directory_)) return;
  if (std::filesystem::exists(directory_)) {
    common::log_warn("can", "left the userspace CAN bus folder " + directory_.string() +
                                ": a member still listens on it, or it holds files that are not the bus's");
  }
}

}  // namespace a3::bridge
