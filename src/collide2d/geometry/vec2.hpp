// Two-dimensional vectors over any collide2d number type, and the motion
// p(t) = p + v t + ½ a t² of a ball. Small inline functions, nothing else.
#pragma once

#include "collide2d/numeric/number_traits.hpp"

namespace collide2d {

template <class Num>
struct Vec2 {
  Num x{};
  Num y{};
};

template <class Num>
inline Vec2<Num> operator+(const Vec2<Num>& a, const Vec2<Num>& b) { return {a.x + b.x, a.y + b.y}; }
template <class Num>
inline Vec2<Num> operator-(const Vec2<Num>& a, const Vec2<Num>& b) { return {a.x - b.x, a.y - b.y}; }
template <class Num>
inline Vec2<Num> operator-(const Vec2<Num>& a) { return {-a.x, -a.y}; }
template <class Num>
inline Vec2<Num> operator*(const Num& s, const Vec2<Num>& a) { return {s * a.x, s * a.y}; }
template <class Num>
inline bool operator==(const Vec2<Num>& a, const Vec2<Num>& b) { return a.x == b.x && a.y == b.y; }

template <class Num>
inline Num dot(const Vec2<Num>& a, const Vec2<Num>& b) { return a.x * b.x + a.y * b.y; }
// z-component of a × b.
template <class Num>
inline Num cross(const Vec2<Num>& a, const Vec2<Num>& b) { return a.x * b.y - a.y * b.x; }
// The same two, accurate to 1.5 ulp even when the terms cancel (strict mode).
template <class Num>
inline Num accurate_dot(const Vec2<Num>& a, const Vec2<Num>& b) {
  return NumberTraits<Num>::diff_of_products(a.x, b.x, -a.y, b.y);
}
template <class Num>
inline Num accurate_cross(const Vec2<Num>& a, const Vec2<Num>& b) {
  return NumberTraits<Num>::diff_of_products(a.x, b.y, a.y, b.x);
}
template <class Num>
inline Num length_squared(const Vec2<Num>& a) { return dot(a, a); }
template <class Num>
inline Num length(const Vec2<Num>& a) { return NumberTraits<Num>::sqrt(length_squared(a)); }
// max(|x|, |y|): the scale a coordinate's rounding is relative to in floating point.
template <class Num>
inline Num largest_magnitude(const Vec2<Num>& a) {
  const Num x = NumberTraits<Num>::abs(a.x), y = NumberTraits<Num>::abs(a.y);
  return x < y ? y : x;
}
// Counter-clockwise perpendicular.
template <class Num>
inline Vec2<Num> perp(const Vec2<Num>& a) { return {-a.y, a.x}; }
// a / |a|; the caller guarantees a ≠ 0.
template <class Num>
inline Vec2<Num> normalized(const Vec2<Num>& a) {
  const Num inv_len = num<Num>(1.0) / length(a);
  return {a.x * inv_len, a.y * inv_len};
}

template <class Num>
inline Vec2<Num> vec2_from_double(double x, double y) { return {num<Num>(x), num<Num>(y)}; }

// A ball's kinematic state at t = 0; it moves as p + v t + ½ a t².
template <class Num>
struct BallState {
  Vec2<Num> position;
  Vec2<Num> velocity;
  Vec2<Num> acceleration;
  Num radius{};
};

// p + v t + ½ a t², evaluated as p + t (v + (t/2) a): one rounding fewer than
// the expanded sum and the same expression in every mode.
template <class Num>
inline Vec2<Num> position_at(const Vec2<Num>& p, const Vec2<Num>& v, const Vec2<Num>& a, const Num& t) {
  const Num half_t = NumberTraits<Num>::half(t);
  return {p.x + t * (v.x + half_t * a.x), p.y + t * (v.y + half_t * a.y)};
}
template <class Num>
inline Vec2<Num> velocity_at(const Vec2<Num>& v, const Vec2<Num>& a, const Num& t) {
  return {v.x + t * a.x, v.y + t * a.y};
}
template <class Num>
inline Vec2<Num> position_at(const BallState<Num>& b, const Num& t) {
  return position_at(b.position, b.velocity, b.acceleration, t);
}
template <class Num>
inline Vec2<Num> velocity_at(const BallState<Num>& b, const Num& t) {
  return velocity_at(b.velocity, b.acceleration, t);
}

// A wall: the segment from a to b, two-sided, with round ends.
template <class Num>
struct Segment {
  Vec2<Num> a;
  Vec2<Num> b;
};

}  // namespace collide2d
