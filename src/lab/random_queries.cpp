#include "lab/random_queries.hpp"

namespace collide2d {

std::string to_string(QueryFamily f) {
  switch (f) {
    case QueryFamily::wall: return "ball_wall";
    case QueryFamily::wall_gravity: return "ball_wall_gravity";
    case QueryFamily::ball_quadratic: return "ball_ball_quadratic";
    case QueryFamily::ball_quartic: return "ball_ball_quartic";
  }
  return "?";
}

const std::vector<QueryFamily>& all_query_families() {
  static const std::vector<QueryFamily> families{QueryFamily::wall, QueryFamily::wall_gravity,
                                                 QueryFamily::ball_quadratic, QueryFamily::ball_quartic};
  return families;
}

namespace {

Vec2<double> random_point(SplitMix64& rng, double half_width) {
  return {rng.uniform(-half_width, half_width), rng.uniform(-half_width, half_width)};
}

// A velocity that points roughly at `target` from `from` half of the time, so
// that about half of the queries hit.
Vec2<double> random_velocity(SplitMix64& rng, const Vec2<double>& from, const Vec2<double>& target) {
  const double speed = rng.uniform(0.5, 10.0);
  Vec2<double> dir = rng.uniform(0, 1) < 0.5 ? target - from : random_point(rng, 1.0);
  dir = dir + random_point(rng, 0.3 * length(dir));
  const double len = length(dir);
  if (len == 0) return {speed, 0};
  return {speed * dir.x / len, speed * dir.y / len};
}

bool overlaps_at_start(const ToiQuery& q) {
  if (q.kind == QueryKind::ball_wall) return distance_to_segment(q.ball.position, q.wall) <= q.ball.radius;
  const double R = q.ball.radius + q.other.radius;
  return length_squared(q.ball.position - q.other.position) <= R * R;
}

}  // namespace

ToiQuery random_query(QueryFamily family, SplitMix64& rng) {
  const Vec2<double> gravity{0, -9.81};
  for (;;) {
    ToiQuery q;
    q.horizon = 1.0;
    q.ball.position = random_point(rng, 5.0);
    q.ball.radius = rng.uniform(0.05, 1.0);
    if (family == QueryFamily::wall || family == QueryFamily::wall_gravity) {
      q.kind = QueryKind::ball_wall;
      const Vec2<double> centre = random_point(rng, 5.0);
      const double angle_x = rng.uniform(-1, 1), angle_y = rng.uniform(-1, 1);
      const double half_length = rng.uniform(0.5, 5.0) / std::max(1e-3, length(Vec2<double>{angle_x, angle_y}));
      q.wall = {{centre.x - half_length * angle_x, centre.y - half_length * angle_y},
                {centre.x + half_length * angle_x, centre.y + half_length * angle_y}};
      q.ball.velocity = random_velocity(rng, q.ball.position, centre);
      if (family == QueryFamily::wall_gravity) q.ball.acceleration = gravity;
    } else {
      q.kind = QueryKind::ball_ball;
      q.other.position = random_point(rng, 5.0);
      q.other.radius = rng.uniform(0.05, 1.0);
      q.ball.velocity = random_velocity(rng, q.ball.position, q.other.position);
      q.ball.acceleration = gravity;
      if (family == QueryFamily::ball_quadratic) {
        q.other.velocity = random_point(rng, 5.0);
        q.other.acceleration = gravity;
      }
    }
    if (!overlaps_at_start(q)) return q;
  }
}

}  // namespace collide2d
