// One of 64 buckets for an object key, from its length and first and last bytes. Keys in
// different buckets differ, so a 64-bit mask of the buckets an object's keys fall in shows
// almost every object free of repeated keys without comparing any. Used by the duplicate-key
// check (json_shape.cpp) and by the simdjson pass (simdjson_parser.cpp), which must agree.
#pragma once

#include <cstdint>
#include <string_view>

namespace a3::eval {

inline uint64_t key_bucket_bit(std::string_view key) {
  if (key.empty()) return 1;
  const unsigned mix = static_cast<unsigned>(key.size()) * 7u +
                       static_cast<unsigned char>(key.front()) * 3u +
                       static_cast<unsigned char>(key.back());
  return uint64_t{1} << (mix & 63u);
}

}  // namespace a3::eval
