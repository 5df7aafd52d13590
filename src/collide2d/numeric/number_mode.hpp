// The number type a run or a query is computed in, chosen at run time, and
// the one place where that choice becomes a type.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include "collide2d/numeric/fixed.hpp"

namespace collide2d {

enum class NumberMode {
  strict,  // IEEE binary64, bit reproducible
  fixed,   // Q63.64 integers, overflow reported
};

// Every mode, in the order commands list them. A new mode goes here, in
// to_string and in with_number_type (whose switches the compiler checks).
inline constexpr std::array<NumberMode, 2> all_number_modes{NumberMode::strict, NumberMode::fixed};

inline std::string_view to_string(NumberMode mode) {
  switch (mode) {
    case NumberMode::strict: return "strict";
    case NumberMode::fixed: return "fixed";
  }
  throw std::logic_error("unknown NumberMode");
}

// "strict" or "fixed"; nothing for any other name.
inline std::optional<NumberMode> number_mode_named(std::string_view name) {
  for (NumberMode m : all_number_modes)
    if (to_string(m) == name) return m;
  return std::nullopt;
}

// Calls f(std::type_identity<Num>{}) with Num the mode's number type, and
// returns what it returns. A generic lambda reads the type back with
//   [&](auto type) { using Num = typename decltype(type)::type; ... }
// The switch names every mode, so the compiler warns when one is added and
// not dispatched here.
template <class F>
decltype(auto) with_number_type(NumberMode mode, F&& f) {
  switch (mode) {
    case NumberMode::strict: return std::forward<F>(f)(std::type_identity<double>{});
    case NumberMode::fixed: return std::forward<F>(f)(std::type_identity<Fixed>{});
  }
  throw std::logic_error("unknown NumberMode");
}

}  // namespace collide2d
