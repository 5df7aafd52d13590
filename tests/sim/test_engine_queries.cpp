// The engine's own query mixes (lab/engine_queries.hpp, `collide2d bench toi
// --families engine_gas,engine_abound`): what the engine asks, as it asks it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "collide2d/geometry/segment_distance.hpp"
#include "lab/engine_queries.hpp"

using namespace collide2d;

namespace {

bool same_bits(const ToiQuery& x, const ToiQuery& y) {
  const auto bits = [](const ToiQuery& q) {
    std::vector<double> v{q.ball.position.x,  q.ball.position.y,  q.ball.velocity.x,  q.ball.velocity.y,
                          q.ball.acceleration.x, q.ball.acceleration.y, q.ball.radius, q.horizon,
                          q.other.position.x, q.other.position.y, q.other.velocity.x, q.other.velocity.y,
                          q.wall.a.x, q.wall.a.y, q.wall.b.x, q.wall.b.y};
    return v;
  };
  const std::vector<double> a = bits(x), b = bits(y);
  return x.kind == y.kind && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("engine queries: the gas mix is what a gas without gravity asks, of neighbours only", "[lab]") {
  const Scene gas = engine_mix_scene("engine_gas");
  const std::vector<ToiQuery> queries = engine_queries(gas, 20000);
  REQUIRE(queries.size() == 20000);
  int walls = 0;
  for (const ToiQuery& q : queries) {
    // No gravity: every motion is linear, so every pair is a quadratic.
    CHECK(q.ball.acceleration.x == 0);
    CHECK(q.ball.acceleration.y == 0);
    CHECK(q.ball.radius == 0.5);
    if (q.kind == QueryKind::ball_ball) CHECK(q.other.radius == 0.5);
    else ++walls;
    // A gas keeps its predictions across record times: a prediction reaches
    // to the run's end, never past it.
    CHECK(q.horizon > 0);
    CHECK(q.horizon <= gas.duration * (1 + 1e-12));
  }
  // 1,000 discs in a box 42 wide: some sit next to a wall, most do not.
  CHECK(walls > 0);
  CHECK(walls < 2000);

  // The first queries are the fresh start at t = 0 (every ball's clock), from
  // the discs' starting places. Cells are w = L / floor(L / side) wide, side
  // = max(2r + 1e-9 L + δ, sqrt(L² / 4N)) (cell_grid.hpp; δ = h_rest = 1e-6
  // r): a pair is asked about only from adjacent cells, within 2√2 w, and a
  // wall only from cells within 2r + δ + 1e-9 L of it, within √2 w of that.
  const double L = gas.walls[0].b[0], r = 0.5, band = 1e-6 * r;
  const double side = std::max(2 * r + 1e-9 * L + band, std::sqrt(L * L / (4 * 1000.0)));
  const double w = L / std::floor(L / side);
  for (std::size_t k = 0; k < 1000; ++k) {
    const ToiQuery& q = queries[k];
    CHECK(q.horizon == gas.duration);
    if (q.kind == QueryKind::ball_ball) CHECK(length(q.ball.position - q.other.position) <= 2 * std::sqrt(2.0) * w);
    else CHECK(distance_to_segment(q.ball.position, q.wall) <= std::sqrt(2.0) * w + 2 * r + band + 2e-9 * L);
  }
}

TEST_CASE("engine queries: the Abound mix has gravity and the scene's walls, and is the same every time", "[lab]") {
  const Scene abound = engine_mix_scene("engine_abound");
  const std::vector<ToiQuery> first = engine_queries(abound, 5000), again = engine_queries(abound, 5000);
  REQUIRE(first.size() == 5000);
  REQUIRE(again.size() == 5000);
  int balls = 0, walls = 0, accelerated = 0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    const ToiQuery& q = first[k];
    CHECK(same_bits(q, again[k]));
    if (q.ball.acceleration.y != 0) ++accelerated;
    if (q.kind == QueryKind::ball_ball) {
      ++balls;
      continue;
    }
    ++walls;
    bool known = false;
    for (const WallSpec& w : abound.walls)
      known = known || (w.a[0] == q.wall.a.x && w.a[1] == q.wall.a.y && w.b[0] == q.wall.b.x && w.b[1] == q.wall.b.y);
    CHECK(known);
  }
  CHECK(balls > 0);
  CHECK(walls > 0);
  CHECK(accelerated > 0);
}
