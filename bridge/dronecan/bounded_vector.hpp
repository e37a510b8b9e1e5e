// A vector with its capacity in its type and its elements inline: the C++ form of a DSDL
// dynamic array (T[<=N]). No heap allocation, so messages can be decoded in a control loop.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

namespace a3::bridge {

template <class T, std::size_t N>
class BoundedVector {
 public:
  using value_type = T;
  static constexpr std::size_t kCapacity = N;

  BoundedVector() = default;
  // Throws std::length_error when init has more than N elements.
  BoundedVector(std::initializer_list<T> init) {
    if (init.size() > N) {
      throw std::length_error("BoundedVector: " + std::to_string(init.size()) +
                              " elements, capacity " + std::to_string(N));
    }
    std::copy(init.begin(), init.end(), items_.begin());
    size_ = init.size();
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  static constexpr std::size_t capacity() { return N; }
  bool full() const { return size_ == N; }

  // Returns false (and changes nothing) when full.
  bool push_back(const T& value) {
    if (size_ == N) return false;
    items_[size_++] = value;
    return true;
  }
  void clear() { size_ = 0; }
  // Throws std::length_error beyond the capacity.
  void resize(std::size_t size) {
    if (size > N) {
      throw std::length_error("BoundedVector: size " + std::to_string(size) + " > capacity " +
                              std::to_string(N));
    }
    for (std::size_t i = size_; i < size; ++i) items_[i] = T{};
    size_ = size;
  }

  T& operator[](std::size_t i) { return items_[i]; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  T* data() { return items_.data(); }
  const T* data() const { return items_.data(); }
  T* begin() { return items_.data(); }
  T* end() { return items_.data() + size_; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + size_; }

  bool operator==(const BoundedVector& other) const {
    return size_ == other.size_ && std::equal(begin(), end(), other.begin());
  }

 private:
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

// Text in a uint8[<=N] field (e.g. BatteryInfo.model_name); throws std::length_error if longer.
template <std::size_t N>
BoundedVector<uint8_t, N> text_array(std::string_view text) {
  if (text.size() > N) {
    throw std::length_error("text of " + std::to_string(text.size()) + " bytes, at most " +
                            std::to_string(N) + ": '" + std::string(text) + "'");
  }
  BoundedVector<uint8_t, N> out;
  for (char c : text) out.push_back(static_cast<uint8_t>(c));
  return out;
}

template <std::size_t N>
std::string array_text(const BoundedVector<uint8_t, N>& bytes) {
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace a3::bridge
