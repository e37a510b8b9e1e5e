// Helpers shared by the bridge suites: hex strings, JSON files, test-vector frames.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bridge/can/can_frame.hpp"

namespace a3::bridge::test {

// "00 02 80" -> {0x00, 0x02, 0x80}
inline std::vector<uint8_t> parse_hex_bytes(const std::string& text) {
  std::vector<uint8_t> out;
  std::istringstream in(text);
  std::string token;
  while (in >> token) out.push_back(static_cast<uint8_t>(std::stoul(token, nullptr, 16)));
  return out;
}

inline std::string to_hex_bytes(const uint8_t* data, std::size_t size) {
  std::string out;
  char buf[4];
  for (std::size_t i = 0; i < size; ++i) {
    std::snprintf(buf, sizeof buf, i == 0 ? "%02x" : " %02x", data[i]);
    out += buf;
  }
  return out;
}

inline nlohmann::json read_json_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

inline CanFrame frame_from_vector(const nlohmann::json& f) {
  CanFrame frame;
  frame.id = static_cast<uint32_t>(std::stoul(f.at("can_id").get<std::string>(), nullptr, 16));
  frame.extended = true;
  const auto bytes = parse_hex_bytes(f.at("data").get<std::string>());
  frame.size = static_cast<uint8_t>(bytes.size());
  for (std::size_t i = 0; i < bytes.size() && i < 8; ++i) frame.data[i] = bytes[i];
  return frame;
}

inline std::filesystem::path local_vectors_path() {
  return std::filesystem::path(A3_SOURCE_DIR) / "tests/data/dronecan/vectors.json";
}

}  // namespace a3::bridge::test
