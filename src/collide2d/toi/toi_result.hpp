// What a time-of-impact query answers.
#pragma once

#include <cstdint>
#include <string_view>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

enum class ToiState { miss, hit };

// Which part of the other object the ball touches first.
enum class ContactFeature : std::uint8_t { none, ball, wall_face, wall_end_a, wall_end_b };

template <class Num>
struct ToiResult {
  ToiState state = ToiState::miss;
  Num time{};              // first contact, in [0, horizon]
  Vec2<Num> point{};       // contact point at that time
  Vec2<Num> normal{};      // unit normal at contact, pointing towards the (first) ball
  ContactFeature feature = ContactFeature::none;
  bool hit() const { return state == ToiState::hit; }
};

// The ways of computing a time of impact, selected by name on the command line.
enum class ToiMethod { analytic, bisection, seed };

inline std::string_view to_string(ToiMethod m) {
  switch (m) {
    case ToiMethod::analytic: return "analytic";
    case ToiMethod::bisection: return "bisection";
    case ToiMethod::seed: return "seed";
  }
  return "?";
}

}  // namespace collide2d
