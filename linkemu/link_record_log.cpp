// JSON Lines writer for link records.
#include "linkemu/link_record_log.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace a3::linkemu {
namespace {

void append_escaped(std::string& out, const std::string& text) {
  out += '"';
  for (unsigned char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  out += '"';
}

void append_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  out += buffer;
}

void append_int(std::string& out, int64_t x) { out += std::to_string(x); }

}  // namespace

const char* outcome_name(int8_t outcome) {
  switch (outcome) {
    case a3lcm::link_record_t::DELIVERED: return "delivered";
    case a3lcm::link_record_t::LOST: return "lost";
    case a3lcm::link_record_t::DROPPED: return "dropped";
  }
  return "unknown";
}

std::string to_json_line(const a3lcm::link_record_t& r) {
  std::string out;
  out.reserve(384);
  out += "{\"t_us\":";
  append_int(out, r.utime_us);
  out += ",\"dir\":";
  append_escaped(out, r.direction);
  out += ",\"id\":";
  append_int(out, r.message_id);
  out += ",\"sender\":";
  append_escaped(out, r.sender);
  out += ",\"kind\":";
  append_escaped(out, r.kind);
  out += ",\"sent_us\":";
  append_int(out, r.sent_utime_us);
  out += ",\"size_bytes\":";
  append_int(out, r.size_bytes);
  out += ",\"outcome\":\"";
  out += outcome_name(r.outcome);
  out += "\",\"drop_reason\":";
  append_escaped(out, r.drop_reason);
  out += ",\"delivery_us\":";
  append_int(out, r.delivery_utime_us);
  out += ",\"queue_ms\":";
  append_number(out, r.queue_ms);
  out += ",\"serialization_ms\":";
  append_number(out, r.serialization_ms);
  out += ",\"latency_ms\":";
  append_number(out, r.latency_ms);
  out += ",\"net\":{\"slice\":";
  append_escaped(out, r.slice);
  out += ",\"lat_ms\":";
  append_number(out, r.net_lat_ms);
  out += ",\"jitter_ms\":";
  append_number(out, r.net_jitter_ms);
  out += ",\"loss_pct\":";
  append_number(out, r.net_loss_pct);
  out += ",\"throughput_mbps\":";
  append_number(out, r.net_throughput_mbps);
  out += ",\"edge_load\":";
  append_number(out, r.net_edge_load);
  out += ",\"degraded\":";
  out += r.net_degraded ? "true" : "false";
  out += "}}\n";
  return out;
}

LinkRecordLog::LinkRecordLog(const std::filesystem::path& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) {
    throw std::runtime_error(path.string() + ": cannot create the link record log: " +
                             std::strerror(errno));
  }
}

LinkRecordLog::~LinkRecordLog() {
  if (file_ != nullptr) std::fclose(file_);
}

void LinkRecordLog::write(const a3lcm::link_record_t& record) {
  if (file_ == nullptr) return;
  const std::string line = to_json_line(record);
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size()) failed_ = true;
  ++lines_;
}

void LinkRecordLog::close() {
  if (file_ == nullptr) return;
  const bool flush_failed = std::fflush(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_ || flush_failed || close_failed) {
    throw std::runtime_error(path_.string() + ": writing the link record log failed");
  }
}

}  // namespace a3::linkemu
