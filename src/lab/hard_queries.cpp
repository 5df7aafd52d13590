#include "lab/hard_queries.hpp"

#include "lab/oracle.hpp"

#include <algorithm>
#include <functional>

namespace collide2d {

namespace {

using V = Vec2<double>;
V operator*(double s, V a) { return {s * a.x, s * a.y}; }
const V gravity{0, -9.81};

V random_point(SplitMix64& rng, double half) { return {rng.uniform(-half, half), rng.uniform(-half, half)}; }

// A wall of length 2·half through a random centre, in a random direction.
Segment<double> random_wall(SplitMix64& rng, double half) {
  const V centre = random_point(rng, 3), d = random_unit(rng);
  return {centre - half * d, centre + half * d};
}

// The builder of one family: adds its queries for one instance (one draw of
// the random parameters) at gap exponent k and sign (0, 0 when the family
// has no gap grid).
using Builder = std::function<void(int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out)>;

struct Family {
  const char* name;
  int k_first, k_last;  // the gap grid, 10^-k of the scale; k_first = 0: none
  int per_instance;     // queries added per call
  Builder build;
};

void add(std::vector<HardQuery>& out, const char* family, const ToiQuery& q, int k, int sign) {
  out.push_back({family, q, k, sign});
}

ToiQuery ball_toward_face(const Segment<double>& w, double r, double along, double speed, double t_contact, V acc) {
  // Perpendicular approach from the side perp(d): contact at t_contact when
  // acc = 0 (a constant acceleration along the normal shifts it).
  const V d = normalized(w.b - w.a), n = perp(d);
  ToiQuery q;
  q.kind = QueryKind::ball_wall;
  q.horizon = 1;
  q.wall = w;
  q.ball = {w.a + along * (w.b - w.a) + (r + speed * t_contact) * n, (-speed) * n, acc, r};
  return q;
}

const std::vector<Family>& families() {
  static const std::vector<Family> list = {
      {"grazing_ball_ball", 3, 15, 6,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const V o = random_point(rng, 5), n = random_unit(rng), u = random_point(rng, 3);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10);
         const double ts = rng.uniform(0.2, 0.8);
         for (const V da : {V{}, gravity, random_point(rng, 10)}) {
           add(out, "grazing_ball_ball",
               at_relative_gap([&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0); }, k, sign), k, sign);
           add(out, "grazing_ball_ball",
               at_relative_gap([&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0, u, gravity); }, k,
                               sign),
               k, sign);
         }
       }},
      {"grazing_wall_face", 3, 15, 1,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const Segment<double> w = random_wall(rng, rng.uniform(3, 10));
         const double r = rng.uniform(0.05, 1), g = rng.uniform(1, 20), slide = rng.uniform(-2, 2);
         const double ts = rng.uniform(0.2, 0.8), along = rng.uniform(0.3, 0.7);
         const int side = rng.uniform(0, 1) < 0.5 ? 1 : -1;
         add(out, "grazing_wall_face",
             at_relative_gap([&](double gp) { return face_turnaround(w.a, w.b, r, along, g, slide, ts, gp, 1.0, side); }, k, sign),
             k, sign);
       }},
      {"grazing_wall_end", 3, 15, 2,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const Segment<double> w = random_wall(rng, rng.uniform(3, 10));
         const V d = normalized(w.b - w.a);
         V n = random_unit(rng);
         if (dot(n, d) < 0.2) n = normalized(n + d + d);  // on the far side of end b
         const double r = rng.uniform(0.05, 1), speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
         for (const V acc : {V{}, random_point(rng, 10)})
           add(out, "grazing_wall_end",
               at_relative_gap([&](double gp) { return end_graze(w.a, w.b, r, n, speed, acc, ts, gp, 1.0); }, k, sign), k, sign);
       }},
      {"tiny_acceleration", 3, 15, 2,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const double speed = rng.uniform(4, 10);  // speed·ts > 2 > R: apart at t = 0
         const V da = (1e-14 * speed) * random_unit(rng), o = random_point(rng, 5), n = random_unit(rng);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), ts = rng.uniform(0.5, 0.9);
         const V u = random_point(rng, 3);
         const auto make = [&](double g) { return ball_ball_graze(o, ra, rb, n, speed, da, ts, g, 1.0, u, u + da); };
         add(out, "tiny_acceleration", at_relative_gap(make, k, sign), k, sign);
         add(out, "tiny_acceleration", make(-ra - rb), 0, 0);  // through the middle: a certain hit
       }},
      {"far_tiny_radii", 3, 15, 5,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const double ts = rng.uniform(0.5, 0.95), dist = 1e7;
         const V n = random_unit(rng), o = dist * random_unit(rng);
         // The gap is ±10^-k of the contact distance here (of the scale,
         // 1e7, it would be far wider than the balls).
         const double gap = sign * ten_to_minus(k);
         for (const double radius : {1e-3, 1e-6})
           for (const V da : {V{}, gravity})
             add(out, "far_tiny_radii", ball_ball_graze(o, radius, radius, n, dist / ts, da, ts, gap * 2 * radius, 1.0), k, sign);
         V side = random_unit(rng);
         if (side.x < 0.2) side = normalized(side + V{2, 0});
         add(out, "far_tiny_radii", end_graze(o - V{1, 0}, o, 1e-6, side, dist / ts, gravity, ts, gap * 1e-6, 1.0), k, sign);
       }},
      {"large_offset", 3, 15, 3,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const V offset{1e8, 1e8};
         const auto shift = [&](ToiQuery q) {
           q.ball.position = q.ball.position + offset;
           q.other.position = q.other.position + offset;
           q.wall = {q.wall.a + offset, q.wall.b + offset};
           return q;
         };
         const V o = random_point(rng, 5), n = random_unit(rng), a = o - 5 * random_unit(rng), g = random_point(rng, 10);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
         V side = random_unit(rng);
         if (dot(side, o - a) < 0.2) side = normalized(side + normalized(o - a) + normalized(o - a));
         add(out, "large_offset",
             at_relative_gap([&](double gp) { return shift(ball_ball_graze(o, ra, rb, n, speed, g, ts, gp, 1.0)); }, k, sign), k,
             sign);
         add(out, "large_offset",
             at_relative_gap([&](double gp) { return shift(face_turnaround(a, o, ra, 0.5, 9.81, 1.0, ts, gp, 1.0, 1)); }, k, sign),
             k, sign);
         add(out, "large_offset",
             at_relative_gap([&](double gp) { return shift(end_graze(a, o, ra, side, speed, V{}, ts, gp, 1.0)); }, k, sign), k,
             sign);
       }},
      {"tiny_radii", 3, 15, 5,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         const double r = 1e-8, speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
         const V o = random_point(rng, 5), n = random_unit(rng), a = o - 5 * random_unit(rng);
         V side = random_unit(rng);
         if (dot(side, o - a) < 0.2) side = normalized(side + normalized(o - a) + normalized(o - a));
         // Gaps of ±10^-k of the radius (of the scale, ~speed, they would
         // dwarf it).
         const double gap = sign * ten_to_minus(k) * r;
         for (const V da : {V{}, gravity}) {
           add(out, "tiny_radii", ball_ball_graze(o, r, r, n, speed, da, ts, 2 * gap, 1.0), k, sign);
           add(out, "tiny_radii", end_graze(a, o, r, side, speed, da, ts, gap, 1.0), k, sign);
         }
         add(out, "tiny_radii", face_turnaround(a, o, r, 0.5, 9.81, 0.5, ts, gap, 1.0, -1), k, sign);
       }},
      {"parallel_sliding", 8, 15, 1,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         // Wall [a, b] of length 10; the ball starts 3 before a on the wall's
         // line offset by r + gap and slides parallel at speed 5 for H = 2.
         const double r = rng.uniform(0.05, 1);
         const V a = random_point(rng, 3), d = random_unit(rng), b = a + 10 * d;
         const double gap = sign * ten_to_minus(k) * std::max(r, 10.0);
         ToiQuery q;
         q.kind = QueryKind::ball_wall;
         q.horizon = 2;
         q.wall = {a, b};
         q.ball = {a - 3 * d + (r + gap) * perp(d), 5 * d, {}, r};
         add(out, "parallel_sliding", q, k, sign);
       }},
      {"near_contact_start", 0, 0, 6,
       [](int, int, SplitMix64& rng, std::vector<HardQuery>& out) {
         const V o = random_point(rng, 5), n = random_unit(rng);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), speed = rng.uniform(1, 10);
         const V tangential = rng.uniform(-2, 2) * perp(n);
         for (const int dir : {-1, 1}) {  // −1: approaching, +1: receding
           ToiQuery q;
           q.kind = QueryKind::ball_ball;
           q.horizon = 1;
           q.other = {o, {}, {}, rb};
           q.ball = {o + (ra + rb + 1e-12) * n, (dir * speed) * n + tangential, {}, ra};
           add(out, "near_contact_start", q, 0, 0);
           ToiQuery w;
           w.kind = QueryKind::ball_wall;
           w.horizon = 1;
           w.wall = {o - 4 * perp(n), o + 4 * perp(n)};
           w.ball = {o + (ra + 1e-12) * n, (dir * speed) * n + tangential, {}, ra};
           add(out, "near_contact_start", w, 0, 0);
           w.ball.acceleration = (-2.5 * speed) * n;  // receding ones come back at t ≈ 0.8
           add(out, "near_contact_start", w, 0, 0);
         }
       }},
      {"contact_at_horizon", 3, 15, 2,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         // Contact at t_c = H (1 + sign 10^-k), H = 1: just inside or just
         // outside the horizon. A wall face approached head on, and a ball
         // falling from rest onto a fixed ball: R + ½ g t_c² above it.
         const double t_c = 1 + sign * ten_to_minus(k);
         // (Each draw named first: the order in which a call's arguments are
         // evaluated differs between compilers.)
         const Segment<double> w = random_wall(rng, rng.uniform(3, 10));
         const double r_wall = rng.uniform(0.05, 1), along = rng.uniform(0.3, 0.7), speed = rng.uniform(1, 10);
         add(out, "contact_at_horizon", ball_toward_face(w, r_wall, along, speed, t_c, V{}), k, sign);
         const V o = random_point(rng, 5), n = random_unit(rng);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), g = rng.uniform(1, 20);
         ToiQuery q;
         q.kind = QueryKind::ball_ball;
         q.horizon = 1;
         q.other = {o, {}, {}, rb};
         q.ball = {o + (ra + rb + 0.5 * g * t_c * t_c) * n, {}, (-g) * n, ra};
         add(out, "contact_at_horizon", q, k, sign);
       }},
      {"endpoints_and_corners", 3, 15, 2,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         // Head on at the seam between a face and its round end: the centre's
         // path passes sign·10^-k of the wall's length beyond (+) or short of
         // (−) end b; linear, and falling under an acceleration along −n.
         const Segment<double> w = random_wall(rng, rng.uniform(3, 10));
         const double along = 1 + sign * ten_to_minus(k);
         const double r = rng.uniform(0.05, 1), speed = rng.uniform(1, 10), ts = rng.uniform(0.2, 0.8);
         const V n = perp(normalized(w.b - w.a));
         add(out, "endpoints_and_corners", ball_toward_face(w, r, along, speed, ts, V{}), k, sign);
         add(out, "endpoints_and_corners", ball_toward_face(w, r, along, speed, ts, (-rng.uniform(1, 20)) * n), k, sign);
       }},
      {"turnaround_gravity", 3, 15, 3,
       [](int k, int sign, SplitMix64& rng, std::vector<HardQuery>& out) {
         // The apex of a throw under gravity grazes a fixed ball (a double
         // root of the quartic: the article's "cubic" case) or a ceiling.
         const V o = random_point(rng, 5), n = random_unit(rng);
         const double ra = rng.uniform(0.05, 1), rb = rng.uniform(0.05, 1), g = rng.uniform(1, 20);
         const double ts = rng.uniform(0.3, 0.8), drift = rng.uniform(0, 0.1);
         for (const double speed : {0.0, drift})
           add(out, "turnaround_gravity",
               at_relative_gap([&](double gp) { return ball_ball_graze(o, ra, rb, n, speed, g * n, ts, gp, 1.0); }, k, sign), k,
               sign);
         const Segment<double> w = random_wall(rng, rng.uniform(3, 10));
         add(out, "turnaround_gravity",
             at_relative_gap([&](double gp) { return face_turnaround(w.a, w.b, ra, 0.5, g, 0.0, ts, gp, 1.0, 1); }, k, sign), k,
             sign);
       }},
      {"random_well_conditioned", 0, 0, 4,
       [](int, int, SplitMix64& rng, std::vector<HardQuery>& out) {
         for (const QueryFamily f : all_query_families()) add(out, "random_well_conditioned", random_query(f, rng), 0, 0);
       }},
  };
  return list;
}

}  // namespace

double ten_to_minus(int k) {
  static const double table[] = {1e0, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
  return table[std::clamp(k, 0, 15)];
}

V random_unit(SplitMix64& rng) {
  for (;;) {
    const V v{rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const double q = length_squared(v);
    if (q > 0.01 && q <= 1) return (1 / std::sqrt(q)) * v;
  }
}

BallState<double> passing_through(V c, V w, V a, double t_star, double r) {
  return {c - t_star * w + (0.5 * t_star * t_star) * a, w - t_star * a, a, r};
}

ToiQuery ball_ball_graze(V o, double r_ball, double r_other, V n, double speed, V da, double t_star, double gap,
                         double horizon, V u, V b) {
  if (dot(n, da) < 0) n = -n;
  const double R = r_ball + r_other;
  ToiQuery q;
  q.kind = QueryKind::ball_ball;
  q.horizon = horizon;
  q.other = {o, u, b, r_other};
  const BallState<double> rel = passing_through((R + gap) * n, speed * perp(n), da, t_star, r_ball);
  q.ball = {o + rel.position, u + rel.velocity, b + rel.acceleration, r_ball};
  return q;
}

ToiQuery end_graze(V a, V b, double r, V n, double speed, V acc, double t_star, double gap, double horizon) {
  ToiQuery q;
  q.kind = QueryKind::ball_wall;
  q.horizon = horizon;
  q.wall = {a, b};
  q.ball = passing_through(b + (r + gap) * n, speed * perp(n), dot(n, acc) < 0 ? -acc : acc, t_star, r);
  return q;
}

ToiQuery face_turnaround(V a, V b, double r, double along, double g, double slide, double t_star, double gap,
                         double horizon, int side) {
  const V d = normalized(b - a);
  const V n = static_cast<double>(side) * perp(d);
  ToiQuery q;
  q.kind = QueryKind::ball_wall;
  q.horizon = horizon;
  q.wall = {a, b};
  q.ball = passing_through(a + along * (b - a) + (r + gap) * n, slide * d, g * n, t_star, r);
  return q;
}

double query_scale(const ToiQuery& q) { return oracle_detail::scale_of(q); }

const std::vector<std::string>& hard_query_families() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Family& f : families()) out.push_back(f.name);
    return out;
  }();
  return names;
}

std::vector<HardQuery> hard_query_set(std::uint64_t seed, int per_family) {
  std::vector<HardQuery> out;
  std::uint64_t stream = 0;
  for (const Family& f : families()) {
    // One random stream per family, so that changing one family's size
    // leaves the others' queries as they were.
    SplitMix64 rng(seed ^ (0x9e3779b97f4a7c15ULL * ++stream));
    const int cells = f.k_first == 0 ? 1 : 2 * (f.k_last - f.k_first + 1);
    const int instances = std::max(1, (per_family + cells * f.per_instance - 1) / (cells * f.per_instance));
    if (f.k_first == 0) {
      for (int i = 0; i < instances; ++i) f.build(0, 0, rng, out);
      continue;
    }
    for (int k = f.k_first; k <= f.k_last; ++k)
      for (const int sign : {1, -1})
        for (int i = 0; i < instances; ++i) f.build(k, sign, rng, out);
  }
  return out;
}

}  // namespace collide2d
