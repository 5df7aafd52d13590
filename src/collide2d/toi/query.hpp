// One time-of-impact query (a ball against a wall or a ball) and its answer
// in any mode by any method. Reading one from a query line is the scene
// parser's job (scene/query_parse.hpp).
#pragma once

#include "collide2d/numeric/number_mode.hpp"
#include "collide2d/toi/analytic.hpp"
#include "collide2d/toi/article_methods.hpp"

namespace collide2d {

enum class QueryKind { ball_wall, ball_ball };

template <class Num>
struct ToiQueryOf {
  QueryKind kind = QueryKind::ball_wall;
  BallState<Num> ball;   // the moving ball
  Segment<Num> wall;     // kind == ball_wall
  WallGeometry<Num> wall_geometry;  // kind == ball_wall: prepared from `wall` by convert_query
  BallState<Num> other;  // kind == ball_ball (fixed: zero velocity and acceleration)
  Num horizon{};
};
using ToiQuery = ToiQueryOf<double>;

template <class Num>
BallState<Num> convert_ball(const BallState<double>& b) {
  return {vec2_from_double<Num>(b.position.x, b.position.y), vec2_from_double<Num>(b.velocity.x, b.velocity.y),
          vec2_from_double<Num>(b.acceleration.x, b.acceleration.y), num<Num>(b.radius)};
}

// The query in number type Num: conversion is exact for doubles the type
// can hold (Fixed: multiples of 2^-64 below 2^63), else rounds or throws.
// A wall is prepared here, once, as a simulator prepares it at load time.
template <class Num>
ToiQueryOf<Num> convert_query(const ToiQuery& q) {
  ToiQueryOf<Num> out;
  out.kind = q.kind;
  out.ball = convert_ball<Num>(q.ball);
  out.wall = {vec2_from_double<Num>(q.wall.a.x, q.wall.a.y), vec2_from_double<Num>(q.wall.b.x, q.wall.b.y)};
  if (q.kind == QueryKind::ball_wall) out.wall_geometry = prepare_wall(out.wall);
  out.other = convert_ball<Num>(q.other);
  out.horizon = num<Num>(q.horizon);
  return out;
}

// Answers a query by `method`. The article had no analytic ball method: its
// ball method is step-and-bisect, so `seed` on a ball–ball query is the
// article's bisection.
template <class Num>
ToiResult<Num> solve_toi_query(const ToiQueryOf<Num>& q, ToiMethod method, const Num& eps) {
  if (q.kind == QueryKind::ball_wall) {
    switch (method) {
      case ToiMethod::analytic: return time_of_impact_ball_wall(q.ball, q.wall_geometry, q.horizon);
      case ToiMethod::bisection: return bisection_ball_wall(q.ball, q.wall, q.horizon, eps);
      case ToiMethod::seed: return seed_ball_wall(q.ball, q.wall, q.horizon);
    }
  }
  if (method == ToiMethod::analytic) return time_of_impact_ball_ball(q.ball, q.other, q.horizon);
  return bisection_ball_ball(q.ball, q.other, q.horizon, eps);
}

// The first contact time as a double, or a miss, in the given mode.
struct QueryAnswer {
  bool hit = false;
  double t = 0;
};
QueryAnswer answer_toi_query(const ToiQuery& q, ToiMethod method, NumberMode mode, double eps);

}  // namespace collide2d
