// The engine's exact state as bytes (a checkpoint), and back. Field by
// field, little-endian as the machine holds it, so the same state always
// gives the same bytes (no struct padding) and restores to the same bits.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {  // T: an integer, double or bool
    if constexpr (std::is_trivially_copyable_v<T>) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
      bytes_.insert(bytes_.end(), p, p + sizeof value);
    } else {  // the studies' high-precision type: never checkpointed
      throw std::logic_error("checkpoints hold integers, doubles and fixed-point values only");
    }
  }
  void put(const Fixed& x) { put(x.raw()); }
  template <class Num>
  void put(const Vec2<Num>& v) {
    put(v.x);
    put(v.y);
  }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}
  template <class T>
  void get(T& value) {
    if constexpr (std::is_trivially_copyable_v<T>) {
      if (at_ + sizeof value > bytes_.size()) throw std::runtime_error("checkpoint state is truncated");
      std::memcpy(&value, bytes_.data() + at_, sizeof value);
      at_ += sizeof value;
    } else {
      throw std::logic_error("checkpoints hold integers, doubles and fixed-point values only");
    }
  }
  void get(Fixed& x) {
    Fixed::Raw raw;
    get(raw);
    x = Fixed::from_raw(raw);
  }
  template <class Num>
  void get(Vec2<Num>& v) {
    get(v.x);
    get(v.y);
  }
  bool done() const { return at_ == bytes_.size(); }
  // Bytes not yet read: a count read from a checkpoint is checked against it
  // before anything of that size is allocated.
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  const std::vector<std::uint8_t>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace collide2d
