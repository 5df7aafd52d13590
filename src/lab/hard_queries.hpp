// Hard time-of-impact queries, by family: the cases where a contact solver
// goes wrong (grazes at ±10^-k of the scale, double roots under gravity,
// tiny radii, far offsets, contacts at the horizon, wall ends and corners).
// The constructors build a query from where and when its closest approach
// happens, so that the gap there is set exactly; `hard_query_set` draws the
// dataset of datasets/hard/ from them with a fixed seed.
//
// Only IEEE-exact operations (+ − × ÷ and sqrt) are used on the way: the
// same seed gives the same queries, bit for bit, on every machine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lab/random_queries.hpp"

namespace collide2d {

// 10^-k for k = 0…15, as exact decimal literals (no libm pow).
double ten_to_minus(int k);

// A unit vector in a uniformly random direction (rejection, then sqrt).
Vec2<double> random_unit(SplitMix64& rng);

// A ball whose centre, moving with acceleration a, passes c at time t_star
// with velocity w there: p(t) = c + w τ + ½ a τ², τ = t − t_star.
BallState<double> passing_through(Vec2<double> c, Vec2<double> w, Vec2<double> a, double t_star, double r);

// Ball–ball query whose relative motion has its closest approach, gap `gap`,
// at t_star: relative position (R + gap) n there, relative velocity
// speed·perp(n), relative acceleration da with n·da ≥ 0 (so τ = 0 is the
// global minimum of the distance). The other ball is at o, moving by (u, b).
ToiQuery ball_ball_graze(Vec2<double> o, double r_ball, double r_other, Vec2<double> n, double speed, Vec2<double> da,
                         double t_star, double gap, double horizon, Vec2<double> u = {}, Vec2<double> b = {});

// Ball passing end b of the wall [a, b] at distance r + gap at t_star, from
// the side n (a unit vector with n·(b − a) > 0, so b is the nearest feature).
ToiQuery end_graze(Vec2<double> a, Vec2<double> b, double r, Vec2<double> n, double speed, Vec2<double> acc,
                   double t_star, double gap, double horizon);

// Ball turning around in front of the face of [a, b] under an acceleration g
// pointing away from it: apex at the point `along` ∈ (0, 1) of the wall, at
// distance r + gap, with velocity `slide` along the wall there.
ToiQuery face_turnaround(Vec2<double> a, Vec2<double> b, double r, double along, double g, double slide,
                         double t_star, double gap, double horizon, int side);

// The query make(gap) with the gap set to sign·10^-k of its scale
// (oracle_detail::scale_of: max(R, |Δv| H, ½ |Δa| H²)).
double query_scale(const ToiQuery& q);
template <class Make>
ToiQuery at_relative_gap(Make make, int k, int sign) {
  return make(sign * ten_to_minus(k) * query_scale(make(0.0)));
}

// One query of the hard dataset: its family and, for the graze families,
// the exponent k and sign of its gap (±10^-k of the scale; k = 0 otherwise).
struct HardQuery {
  std::string family;
  ToiQuery query;
  int gap_exponent = 0;
  int gap_sign = 0;
};

// The families of hard_query_set, in the order it produces them.
const std::vector<std::string>& hard_query_families();

// About `per_family` queries of every family (each a little over, rounded
// to whole grid cells), drawn from `seed`.
std::vector<HardQuery> hard_query_set(std::uint64_t seed, int per_family);

}  // namespace collide2d
