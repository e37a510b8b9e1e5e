// Helpers for the common/ suites: a scoped environment variable, a temporary folder,
// and a thread that runs a blocking call with a deadline (so a hang fails, not stalls).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <thread>

namespace a3::test {

// Sets (or unsets, with nullopt) an environment variable and restores it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(std::string name, const std::optional<std::string>& value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    if (value) {
      ::setenv(name_.c_str(), value->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

// A fresh folder under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "a3rig-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Runs `body` in a thread. join_within() waits up to `limit`; when the thread is still
// running then, it calls `unblock` (e.g. a second stop()) so the test can fail cleanly.
class DeadlineThread {
 public:
  explicit DeadlineThread(std::function<void()> body) {
    std::packaged_task<void()> task(std::move(body));
    done_ = task.get_future();
    thread_ = std::thread(std::move(task));
  }
  ~DeadlineThread() {
    if (thread_.joinable()) thread_.join();
  }
  DeadlineThread(const DeadlineThread&) = delete;
  DeadlineThread& operator=(const DeadlineThread&) = delete;

  // True when the body finished in time; rethrows what the body threw.
  bool join_within(std::chrono::milliseconds limit, const std::function<void()>& unblock) {
    const bool finished = done_.wait_for(limit) == std::future_status::ready;
    if (!finished) {
      while (done_.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
        unblock();
      }
    }
    thread_.join();
    done_.get();
    return finished;
  }

 private:
  std::future<void> done_;
  std::thread thread_;
};

}  // namespace a3::test
