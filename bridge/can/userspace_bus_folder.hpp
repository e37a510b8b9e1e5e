// Cleaning up after a program that starts the members of a userspace CAN bus (`a3rig run`, whose
// bus is "userspace:a3rig-run-<pid>"): the last member to leave removes the bus's folder itself,
// but a member can crash, and a whole run can be killed (SIGKILL) before anyone leaves.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "bridge/can/userspace_bus.hpp"

namespace a3::bridge {

// Removes, under root, the bus folders named <prefix><pid> whose process is gone and that no
// member listens on. Returns how many it removed. Never throws.
std::size_t remove_userspace_buses_of_dead_runs(const std::filesystem::path& root, const std::string& prefix);

// While it lives, the program runs the members of the bus `can_spec` names; when it goes out of
// scope (the normal end, an exception, a stop by SIGTERM), the bus's folder is removed if no
// member is left. For a spec that is not a userspace bus it does nothing. A bus named after this
// process (<prefix><pid>, as a3rig-run-<pid>) is a per-run bus: on construction the folders of
// <prefix><pid> buses whose process is gone are removed too. Never throws.
class UserspaceBusFolderGuard {
 public:
  explicit UserspaceBusFolderGuard(const std::string& can_spec, const UserspaceCanOptions& options = {});
  ~UserspaceBusFolderGuard();
  UserspaceBusFolderGuard(const UserspaceBusFolderGuard&) = delete;
  UserspaceBusFolderGuard& operator=(const UserspaceBusFolderGuard&) = delete;

  // The bus's folder; empty when the spec is not a userspace bus.
  const std::filesystem::path& directory() const { return directory_; }

 private:
  std::filesystem::path directory_;
};

}  // namespace a3::bridge
