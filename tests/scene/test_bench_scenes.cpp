// The benchmark scenes (lab/bench_scenes.hpp), the scene writer, and the
// overlap check's grid against the plain double loop it replaced.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include <nlohmann/json.hpp>

#include "collide2d/scene/scene.hpp"
#include "lab/bench_scenes.hpp"

using namespace collide2d;

namespace {

// What the overlap check answered before it had a grid: the first pair in
// (i, then k > i, then walls) order, as the error's text.
std::string brute_force_overlap(const Scene& s) {
  const double rounding = 8 * std::numeric_limits<double>::epsilon();
  for (std::size_t i = 0; i < s.balls.size(); ++i)
    for (std::size_t k = i + 1; k < s.balls.size(); ++k) {
      const double R = s.balls[i].radius + s.balls[k].radius;
      const double d = std::hypot(s.balls[k].position[0] - s.balls[i].position[0], s.balls[k].position[1] - s.balls[i].position[1]);
      if (R - d > rounding * (d + R))
        return "balls[" + std::to_string(k) + "]: overlaps balls[" + std::to_string(i) + "] at t = 0";
    }
  return "";
}

std::string overlap_error(const Scene& s) {
  try {
    check_no_initial_overlap(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("bench scenes: the grid overlap check names the pair the double loop names", "[scene][bench]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> where(0, 20), size(0.1, 1.5);
  int overlapping = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Scene s;
    const int n = 2 + trial % 40;
    for (int k = 0; k < n; ++k) {
      BallSpec b;
      b.position = {where(rng), where(rng)};
      b.radius = size(rng);
      s.balls.push_back(b);
    }
    const std::string expected = brute_force_overlap(s);
    overlapping += expected.empty() ? 0 : 1;
    CHECK(overlap_error(s) == expected);
  }
  CHECK(overlapping > 50);  // both answers were exercised
  CHECK(overlapping < 200);
}

TEST_CASE("bench scenes: a written scene reads back to the same scene", "[scene][bench]") {
  Scene s = hard_disk_gas(10, 0.3, 1, 5, 10);
  s.gravity = {0, -2};
  s.balls[3].fixed = true;
  s.balls[3].velocity = {0, 0};
  s.balls[4].acceleration = Point{1, 0.5};
  s.balls[5].mass = 2.5;
  s.balls[6].restitution = 0.25;
  s.rest.height = 1e-4;
  s.balls[7].mass = 1 + 0x1p-52;
  s.balls[8].restitution = std::nextafter(s.restitution, 0.0);  // differs from the default by one ulp
  for (const bool one_ball_a_line : {false, true}) {
  INFO((one_ball_a_line ? "one ball a line" : "every value written"));
  const std::string text = one_ball_a_line ? scene_to_json_one_ball_a_line(s) : scene_to_json(s);
  const Scene back = parse_scene(parse_json_text(text));
  CHECK(back.name == s.name);
  CHECK(back.gravity == s.gravity);
  CHECK(back.duration == s.duration);
  CHECK(back.record_interval == s.record_interval);
  CHECK(back.rest.height == s.rest.height);
  CHECK(!back.rest.speed);
  REQUIRE(back.walls.size() == s.walls.size());
  REQUIRE(back.balls.size() == s.balls.size());
  for (std::size_t k = 0; k < s.balls.size(); ++k) {
    CHECK(back.balls[k].position == s.balls[k].position);  // to the bit
    CHECK(back.balls[k].velocity == s.balls[k].velocity);
    CHECK(back.balls[k].mass == s.balls[k].mass);
    CHECK(back.balls[k].restitution == s.balls[k].restitution);
    CHECK(back.balls[k].fixed == s.balls[k].fixed);
    CHECK(back.balls[k].acceleration == s.balls[k].acceleration);
  }
  if (one_ball_a_line) {
    // Each ball on a line of its own, the defaults left out.
    auto occurrences = [&](const std::string& what) {
      std::size_t n = 0;
      for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
      return n;
    };
    CHECK(occurrences("\n  {") == s.balls.size());
    CHECK(occurrences("\"fixed\"") == 1);  // ball 3
    CHECK(occurrences("\"mass\"") == 2);   // balls 5 and 7
  }
  }
}

TEST_CASE("bench scenes: a hard-disk gas has the packing fraction and speeds asked for", "[scene][bench]") {
  for (double eta : {0.1, 0.3, 0.45})
    for (std::int64_t n : {1, 7, 1000, 4001}) {
      const Scene s = hard_disk_gas(n, eta, 2.0, 3.0, 20);
      REQUIRE(static_cast<std::int64_t>(s.balls.size()) == n);
      const double side = s.walls[0].b[0];
      double area = 0;
      for (const BallSpec& b : s.balls) {
        area += std::numbers::pi * b.radius * b.radius;
        CHECK(std::hypot(b.velocity[0], b.velocity[1]) == Approx(2.0).epsilon(1e-15));
        CHECK(b.position[0] > b.radius);
        CHECK(b.position[0] < side - b.radius);
        CHECK(b.position[1] > b.radius);
        CHECK(b.position[1] < side - b.radius);
      }
      CHECK(area / (side * side) == Approx(eta).epsilon(1e-12));
      CHECK_NOTHROW(check_no_initial_overlap(s));
      CHECK(s.record_interval * 20 == Approx(3.0));
    }
}

// Enskog's rate against its low-density limit, the kinetic theory of a dilute
// gas: ω = 2σ n sqrt(π kT/m) with g(σ) → 1 (within 1 % at η = 0.01:
// Henderson's g(σ) − 1 ≈ (2 − 7/16) η = 1.6 %·η/0.01).
TEST_CASE("bench scenes: the collision rate goes to the dilute-gas limit", "[scene][bench]") {
  const std::int64_t n = 1000;
  const double eta = 1e-4, speed = 1;
  const double side = std::sqrt(n * std::numbers::pi * 0.25 / eta);
  const double dilute = n * (2 * 1.0 * (n / (side * side)) * std::sqrt(std::numbers::pi * speed * speed / 2)) / 2;
  CHECK(hard_disk_collision_rate(n, eta, speed) == Approx(dilute).epsilon(2e-4));
}
