// The per-message log: one JSON object per line for every link_record_t, the file a later
// stage attaches to the episode (each turn's `net` vector is the n_t of its messages).
//   {"t_us":..,"dir":"up","id":..,"sender":"agent","kind":"mcp_call","sent_us":..,
//    "size_bytes":..,"outcome":"delivered|lost|dropped","drop_reason":"",
//    "delivery_us":..,"queue_ms":..,"serialization_ms":..,"latency_ms":..,
//    "net":{"slice":"eMBB","lat_ms":..,"jitter_ms":..,"loss_pct":..,"throughput_mbps":..,
//           "edge_load":..,"degraded":false}}
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "a3lcm/link_record_t.hpp"

namespace a3::linkemu {

std::string to_json_line(const a3lcm::link_record_t& record);
const char* outcome_name(int8_t outcome);

class LinkRecordLog {
 public:
  // Creates (truncates) the file; throws std::runtime_error naming it when it cannot.
  explicit LinkRecordLog(const std::filesystem::path& path);
  ~LinkRecordLog();
  LinkRecordLog(const LinkRecordLog&) = delete;
  LinkRecordLog& operator=(const LinkRecordLog&) = delete;

  void write(const a3lcm::link_record_t& record);
  // Flushes and closes; throws std::runtime_error when a write failed.
  void close();
  uint64_t lines() const { return lines_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  uint64_t lines_ = 0;
  bool failed_ = false;
};

}  // namespace a3::linkemu
