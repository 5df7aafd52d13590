// A Fixed as two 64-bit words, the form its exact value takes in a run file
// (HDF5 and h5py have no 128-bit integers):
//   hi  the high word, signed (raw >> 64, arithmetic shift)
//   lo  the low word's bits, unsigned in meaning, stored in an int64
//   value = (hi * 2^64 + (uint64)lo) / 2^64, i.e. raw = hi * 2^64 + (uint64)lo
// Every Fixed has exactly one such pair and every pair is a Fixed.
#pragma once

#include <cstdint>

#include "collide2d/numeric/fixed.hpp"

namespace collide2d {

struct FixedWords {
  std::int64_t hi = 0;
  std::int64_t lo = 0;  // bit pattern of the unsigned low word
};

inline FixedWords to_words(const Fixed& x) {
  const auto bits = static_cast<fixed_detail::UInt128>(x.raw());
  return {static_cast<std::int64_t>(fixed_detail::hi64(bits)), static_cast<std::int64_t>(fixed_detail::lo64(bits))};
}

inline Fixed from_words(std::int64_t hi, std::int64_t lo) {
  // hi * 2^64 + (uint64)lo, formed in unsigned arithmetic (no signed overflow)
  // and converted back: C++20 defines the modular conversion.
  const auto bits = fixed_detail::make128(static_cast<std::uint64_t>(hi), static_cast<std::uint64_t>(lo));
  return Fixed::from_raw(static_cast<Fixed::Raw>(bits));
}

}  // namespace collide2d
