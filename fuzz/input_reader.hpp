// Takes a fuzz input apart: fixed-size numbers from the front, then the rest as text or bytes.
// Reading past the end gives zeros, so every input is usable.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "fuzz/fuzz_target.hpp"

namespace a3::fuzz {

class InputReader {
 public:
  explicit InputReader(Input input) : input_(input) {}

  bool empty() const { return input_.empty(); }
  std::size_t remaining() const { return input_.size(); }

  std::uint8_t byte() { return take<std::uint8_t>(); }
  std::uint32_t u32() { return take<std::uint32_t>(); }
  float f32() { return take<float>(); }

  // Up to `n` bytes (fewer at the end).
  Input bytes(std::size_t n) {
    const std::size_t count = n < input_.size() ? n : input_.size();
    const Input out = input_.first(count);
    input_ = input_.subspan(count);
    return out;
  }
  // Everything up to the next '\n' (taken and dropped), or the rest.
  std::string line() {
    const auto* begin = reinterpret_cast<const char*>(input_.data());
    const std::string_view rest(begin, input_.size());
    const std::size_t end = rest.find('\n');
    const std::string out(rest.substr(0, end));
    input_ = input_.subspan(end == std::string_view::npos ? input_.size() : end + 1);
    return out;
  }
  std::string rest() {
    const Input all = bytes(input_.size());
    return std::string(reinterpret_cast<const char*>(all.data()), all.size());
  }

 private:
  template <class T>
  T take() {
    T value{};
    const Input raw = bytes(sizeof(T));
    if (!raw.empty()) std::memcpy(&value, raw.data(), raw.size());
    return value;
  }

  Input input_;
};

}  // namespace a3::fuzz
