// Pinches and wedges without gravity: a ball driven between two immovable
// partners (walls' faces or ends, fixed balls), where its bounces meet at
// one instant (src/collide2d/sim/pinch.hpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "engine_runs.hpp"

using namespace collide2d;
using namespace collide2d::test;

namespace {
// Zero gravity; a floor (restitution 1) and a fixed ball of radius R whose
// lowest point is a diameter 2r above it: a pinch exactly the ball's width
// at x = 0. The ball (radius r, restitution 0.9) slides along the floor at
// speed u with a normal speed w0 off it.
constexpr double kPinchR = 0.5, kPinchr = 0.25, kPinchU = 1.0, kPinchW0 = 1e-6;
Scene ball_sliding_through_a_pinch() {
  Scene s;
  s.gravity = {0, 0};
  s.duration = 3.0;
  s.record_interval = 0.01;
  s.walls = {{{-10, 0}, {10, 0}, 1.0}};
  BallSpec fixed = ball(0, 2 * kPinchr + kPinchR, 0, 0, kPinchR);
  fixed.fixed = true;
  s.balls = {ball(-2, kPinchr, kPinchU, kPinchW0, kPinchr, 1, 0.9), fixed};
  return s;
}
}  // namespace

TEST_CASE("engine: a ball slides through a pinch exactly its diameter wide without gravity", "[sim]") {
  // The property suite's stalls (datasets/regressions/*-pinch-*, *-stall):
  // the ball bounces between floor and fixed ball ever faster as the gap
  // closes, and in floating or fixed point the bounces meet at one instant
  // with normals a rounding angle off opposite, ringing for ever
  // (pinch.hpp). In exact arithmetic it passes, slowed only by the series
  // on the way in. At offset x from the pinch the fixed ball's normal leans
  // by α = |x| / (R + r) and the clearance is c = x² / (2 (R + r)). Each
  // bounce off the fixed ball feeds (1 + e) u α into the normal speed and
  // each bounce multiplies it by e, so it settles at w = u α / (1 − e); each
  // bounce off the fixed ball takes (1 + e) w α from u, one per 2c / w of
  // time, u 2c / w = (1 − e) |x| of way. So d ln u / dx = −(1 + e) |x| /
  // ((1 − e)² (R + r)²), and from where the ring starts, x0, to the pinch
  // ln(u / u0) = −(1 + e) x0² / (2 (1 − e)² (R + r)²). The ball first meets
  // the fixed ball where it has risen w0 t ≈ 2e-6 (t ≈ 2 s): x0² = 2 (R + r)
  // 2e-6, so u / u0 = 1 − 5.1e-4 (first order in α, an upper bound on the
  // loss: the ring takes a few bounces to build up; checked to twice that).
  // The pinch rule takes only what normal speed is left (below u α0 /
  // (1 − e) ≈ 2.3e-2), so the energy the rest rules took is at most
  // ½ m (2.3e-2)². Without the rule this scene stalls (e = 0.5 does not: its
  // ring decays below the creep speed before the rounding angle feeds it).
  const Scene s = ball_sliding_through_a_pinch();
  for (const Recorded& r : {run<double>(s, 3.0), run<Fixed>(s, 3.0)}) {
    const FrameRecord& last = r.frames.back();
    CHECK(last.position[0] > 0.5);  // through the pinch at x = 0, on along the floor
    CHECK(last.velocity[0] == Approx(kPinchU).epsilon(1.02e-3));
    CHECK(last.velocity[0] < kPinchU);
    CHECK(std::fabs(last.velocity[1]) < 2.3e-2);
    CHECK(r.summary.deepest_overlap < 1e-6 * kPinchr);
    CHECK(r.summary.energy_removed_by_rest <= 0.5 * 2.3e-2 * 2.3e-2);
    CHECK(last.energy <= r.frames.front().energy);
  }
}

TEST_CASE("engine: a ball passes between two wall ends exactly its diameter apart without gravity", "[sim]") {
  // A funnel's mouth (datasets/regressions/momentum-kept-strict-1-funnel-
  // stall.json): two walls ending at (±r, 0), the ball (radius r, e = 0.9)
  // falling through at u = 1 with a sideways speed of 1e-7. Both ends are
  // round partners on one axis through the ball's centre at the pinch: the
  // pinch rule answers along it and the fall goes on. On the way in, as in
  // the test above but with both sides leaning by α = |y| / r and a
  // clearance y² / r: w = (1 + e) u α / (1 − e), one bounce per (1 − e) |y|
  // / (1 + e) of way, d ln u / dy = −(1 + e)³ |y| / ((1 − e)² r²), and
  // ln(u / u0) = −(1 + e)³ y0² / (2 (1 − e)² r²) from the first touch at
  // y0² = 2 r · 1e-7 (offset 1e-7 after the 1 s fall): u / u0 = 1 − 2.7e-4
  // (checked to twice that). The sideways speed can only shrink. Without the
  // rule this scene stalls.
  Scene s;
  s.gravity = {0, 0};
  s.duration = 3.0;
  s.record_interval = 0.01;
  s.walls = {{{-3, 1}, {-0.25, 0}, 1.0}, {{0.25, 0}, {3, 1}, 1.0}};
  s.balls = {ball(0, 1, 1e-7, -1, 0.25, 1, 0.9)};
  for (const Recorded& r : {run<double>(s, 3.0), run<Fixed>(s, 3.0)}) {
    const FrameRecord& last = r.frames.back();
    CHECK(last.position[1] < -1.5);  // fell through the mouth at y = 0
    CHECK(last.velocity[1] == Approx(-1.0).epsilon(5.5e-4));
    CHECK(last.velocity[1] > -1.0);
    CHECK(std::fabs(last.velocity[0]) <= 1e-7);
    CHECK(r.summary.deepest_overlap < 1e-6 * 0.25);
    CHECK(last.energy <= r.frames.front().energy);
  }
}

TEST_CASE("engine: a ball beside a fixed ball that another ball strikes at the same instant is no pinch", "[sim]") {
  // (Found by review.) Ball Y rattles between a wall and a fixed ball with
  // a clearance of 1.25e-7 (a pinch's geometry); ball X strikes the fixed
  // ball from the other side at the instant Y does. The fixed ball was
  // struck at that instant, Y was not struck again: no jam, so the pinch
  // rule must not stop Y. Y rings down by restitution alone (e = 0.9 a
  // bounce, one per 1.25e-7 / |v| s: still moving after 0.01 s), and the
  // rest rules take nothing.
  Scene s;
  s.gravity = {0, 0};
  s.duration = 1.0;
  s.record_interval = 0.01;
  s.walls = {{{1.000000125, -5}, {1.000000125, 5}, 1.0}};
  BallSpec fixed = ball(0, 0, 0, 0, 0.5);
  fixed.fixed = true;
  s.balls = {ball(-0.7500000625, 0, 1, 0, 0.25, 1, 0.9), fixed, ball(0.7500000625, 0, -1, 0, 0.25, 1, 0.9)};
  for (const Recorded& r : {run<double>(s, 1.0), run<Fixed>(s, 1.0)}) {
    CHECK(r.summary.energy_removed_by_rest == 0);
    REQUIRE(r.frames.size() > 1);
    CHECK(std::fabs(r.frames[1].velocity[4]) > 0);
    CHECK(r.frames.back().velocity[0] == Approx(-0.9).epsilon(1e-12));  // X bounced off the fixed ball
  }
}

namespace {
// No rule adds energy: it never rises from frame to frame beyond rounding,
// 1e-12 of its scale.
void check_energy_never_rises(const Recorded& r, double scale) {
  for (std::size_t k = 1; k < r.frames.size(); ++k)
    CHECK(r.frames[k].energy <= r.frames[k - 1].energy + 1e-12 * scale);
}

// The pinch scene's fixed ball lowered by δ' (a gap narrower than the ball:
// a wedge), or the floor replaced by a second fixed ball mirrored about
// y = 0 (the two lowered by δ'/2 each, a wedge between two fixed balls,
// the ball sliding along y = 0).
Scene ball_driven_into_a_wedge(double narrower_by, bool between_fixed_balls) {
  Scene s;
  s.gravity = {0, 0};
  s.duration = 1.0;
  s.record_interval = 0.01;
  if (between_fixed_balls) {
    const double y = kPinchr + kPinchR - narrower_by / 2;
    BallSpec above = ball(0, y, 0, 0, kPinchR), below = ball(0, -y, 0, 0, kPinchR);
    above.fixed = below.fixed = true;
    s.walls = {{{-10, -5}, {10, -5}, 1.0}};  // far away: never met
    s.balls = {ball(-0.5, 0, kPinchU, kPinchW0, kPinchr, 1, 0.9), above, below};
  } else {
    BallSpec fixed = ball(0, 2 * kPinchr + kPinchR - narrower_by, 0, 0, kPinchR);
    fixed.fixed = true;
    s.walls = {{{-10, 0}, {10, 0}, 1.0}};
    s.balls = {ball(-0.5, kPinchr, kPinchU, kPinchW0, kPinchr, 1, 0.9), fixed};
  }
  return s;
}

// The series of strikes at one instant between two sides of unit normals
// n1, n2 (pointing at the ball), by the textbook reflection: the limit
// speed, or -1 if it has not ended after a million strikes.
double speed_after_ring(double vx, double vy, const double n1[2], const double n2[2], double e) {
  for (int k = 0; k < 1000000; ++k) {
    const double d1 = vx * n1[0] + vy * n1[1], d2 = vx * n2[0] + vy * n2[1];
    const double* n = d1 < d2 ? n1 : n2;
    const double d = d1 < d2 ? d1 : d2;
    if (d >= 0) return std::hypot(vx, vy);
    vx -= (1 + e) * d * n[0];
    vy -= (1 + e) * d * n[1];
  }
  return -1;
}

// A V of two walls (restitution 1), `length` long, at ±θ from the vertical
// about the origin (its normals α = 2θ off opposite), without gravity; a
// ball (radius kPinchr, restitution e) falls along its axis at speed 1 from
// y = start. `expected`: the speed the textbook series of strikes at the
// instant it meets both walls leaves it with.
struct BallIntoV {
  Scene scene;
  double expected;
};
BallIntoV ball_falling_into_a_v(double theta, double length, double start, double e, double duration,
                                double record_interval) {
  BallIntoV v;
  v.scene.gravity = {0, 0};
  v.scene.duration = duration;
  v.scene.record_interval = record_interval;
  v.scene.walls = {{{0, 0}, {-length * std::sin(theta), length * std::cos(theta)}, 1.0},
                   {{0, 0}, {length * std::sin(theta), length * std::cos(theta)}, 1.0}};
  v.scene.balls = {ball(0, start, 0, -1, kPinchr, 1, e)};
  const double n1[2] = {std::cos(theta), std::sin(theta)}, n2[2] = {-std::cos(theta), std::sin(theta)};
  v.expected = speed_after_ring(0, -1, n1, n2, e);
  return v;
}
}  // namespace

TEST_CASE("engine: a ball driven into a wedge without gravity collapses there instead of stalling", "[sim]") {
  // A review's scenes: the gap is narrower than the ball by δ' = δ/2 or 2δ
  // (δ = h_rest = 1e-6 r, the scene's contact band), between the floor and
  // a fixed ball, or between two fixed balls. Where the ball touches both
  // sides the normals are α off opposite, α² = 2 δ' / (R + r) against the
  // floor and 4 δ' / (R + r) between the balls (α ~ 1e-3). For e = 0.9,
  // (1 + e) sin α < 1 − e: the series of strikes at one instant collapses
  // (pinch.hpp), its speed falling to zero without turning back (a
  // particle's inelastic collapse into a wedge). Without the wedge rule
  // both modes stall (10^5 events at one instant). The limit is rest
  // touching both sides: the ball stops at x = −sqrt(2 (R + r) δ' − δ'²)
  // (the floor case; the mirrored case at −sqrt((R + r)² − (R + r −
  // δ'/2)²)), within the band δ of each, and everything it had is taken by
  // the rule or by the restitution before.
  const double delta = 1e-6 * kPinchr;
  for (const double narrower_by : {delta / 2, 2 * delta}) {
    for (const bool between_fixed_balls : {false, true}) {
      const Scene s = ball_driven_into_a_wedge(narrower_by, between_fixed_balls);
      const double sum = kPinchR + kPinchr;
      const double lowered = between_fixed_balls ? narrower_by / 2 : narrower_by;
      // |x| where the ball would touch both sides with gaps up to δ (the
      // band's slack).
      const double slack_x = std::sqrt(sum * sum - (sum - lowered - delta) * (sum - lowered - delta));
      for (const Recorded& r : {run<double>(s, 1.0), run<Fixed>(s, 1.0)}) {
        INFO("narrower by " << narrower_by << (between_fixed_balls ? ", two fixed balls" : ", floor and fixed ball"));
        const FrameRecord& last = r.frames.back();
        const double x = last.position[0], y = last.position[1];
        CHECK(x < 0);  // stopped before the narrowest point
        CHECK(x > -slack_x);
        CHECK(std::hypot(last.velocity[0], last.velocity[1]) < 1e-6 * kPinchU);
        // Touching both sides (within the band): the upper fixed ball, and
        // the floor or the lower one.
        const double y_above = (between_fixed_balls ? kPinchr : 2 * kPinchr) + kPinchR - lowered;
        const double gap_above = std::hypot(x, y_above - y) - sum;
        const double gap_below = between_fixed_balls ? std::hypot(x, y + y_above) - sum : y - kPinchr;
        CHECK(gap_above > -1e-6 * kPinchr);
        CHECK(gap_above < delta);
        CHECK(gap_below > -1e-6 * kPinchr);
        CHECK(gap_below < delta);
        CHECK(r.summary.deepest_overlap < 1e-6 * kPinchr);
        CHECK(r.summary.counters.rest.came_to_rest >= 1);
        check_energy_never_rises(r, r.frames.front().energy);
      }
    }
  }
}

TEST_CASE("engine: a ball thrown into a wedge whose series turns it back leaves with the series' speed", "[sim]") {
  // A V of two walls (restitution 1) at ±θ from the vertical, θ = 0.05, so
  // the normals are α = 2θ = 0.1 off opposite; the ball (e = 0.9) falls
  // along the V's axis and meets both walls at one instant (to rounding).
  // The textbook series of strikes there ends after 37, the ball turned
  // back up at a seventh of its speed: no collapse, so the wedge rule must
  // leave it to the engine's events (the rule would stop the ball dead).
  const auto [s, expected] = ball_falling_into_a_v(0.05, 20, 10, 0.9, 20.0, 0.5);
  REQUIRE(expected > 0.14);  // the series ends (0.1428...)
  for (const Recorded& r : {run<double>(s, 12.0), run<Fixed>(s, 12.0)}) {
    const FrameRecord& last = r.frames.back();
    CHECK(std::hypot(last.velocity[0], last.velocity[1]) == Approx(expected).epsilon(1e-6));
    CHECK(last.velocity[1] > 0);  // going back up
    CHECK(r.summary.energy_removed_by_rest == 0);
    CHECK(r.summary.deepest_overlap < 1e-6 * kPinchr);
  }
}

TEST_CASE("engine: a ball falling through a funnel's mouth exactly its width under gravity gains nothing from the rules",
          "[sim]") {
  // Two walls ending at (±r, 0), the ball (radius r, e = 0.9) dropped from
  // y = 1 a hair (1e-9, 1e-7) or a little (3e-3) right of the axis. It lands
  // on the right end, is held there (gravity presses it on), rattles and
  // slides down into the mouth, where the left end strikes it at the instant
  // of its last strike: a pinch, with a contact already held on the other
  // side a rounding angle off the axis. That contact must be turned onto
  // the axis with the strike (align_other_side): left as it was, the
  // plastic impact of two normals not quite opposite took the ball for
  // locked, and the rules put energy in (the run's "rest rules took" came
  // to −0.54 and −0.016). Frictionless, nothing can hold a ball in a gap its
  // own width: it falls through. No rule adds energy: what the rules took is
  // not negative, and the energy never rises from frame to frame beyond
  // rounding (1e-12 of its scale, 9.81 here).
  const double r = 0.25;
  for (const double offset : {1e-9, 1e-7, 3e-3}) {
    Scene s;
    s.gravity = {0, -9.81};
    s.duration = 2.0;
    s.record_interval = 0.01;
    s.walls = {{{-3, 1}, {-r, 0}, 1.0}, {{r, 0}, {3, 1}, 1.0}, {{-5, -3}, {5, -3}, 1.0}};
    s.balls = {ball(offset, 1, 0, 0, r, 1, 0.9)};
    for (const Recorded& run_ : {run<double>(s, 2.0), run<Fixed>(s, 2.0)}) {
      INFO("offset " << offset);
      CHECK(run_.summary.energy_removed_by_rest >= 0);
      check_energy_never_rises(run_, std::fabs(run_.frames.front().energy));
      // Through the mouth: a diameter below it at some frame (the floor at
      // y = −3 throws it back up to about 0.81 of its fall, near the mouth).
      bool through = false;
      for (const FrameRecord& f : run_.frames) through = through || f.position[1] < -2 * r;
      CHECK(through);
      CHECK(run_.summary.deepest_overlap < 1e-6 * r);
    }
  }
}

TEST_CASE("engine: a wedge narrower than the ball by 1e-12 lets nothing sink", "[sim]") {
  // (Found by review.) δ' = 1e-12: α ≈ 1.6e-6 against the floor, below
  // 2^-15, where the island's complementarity problem cannot tell the two
  // normals from opposite: it dropped the second as redundant, the floor
  // contact was left closing, and the ball sank into the floor at 1.6e-6
  // m/s (6.4e-6 r deep after 1 s, 1.4e-5 after 9 s). Now such a wedge is a
  // pinch to the engine (answered along the struck normal, overlapping by at
  // most δ' = 4e-12 r where it passes). Which rule meets the ball depends on
  // the history: in strict mode the bounces ring at one instant and the
  // pinch lets it pass; in fixed mode it is first held sliding on the floor,
  // and the fixed ball's strike then acts along the one direction the floor
  // leaves free, turning it back at e u. Either way it leaves the wedge at
  // about its speed, nothing is ever deeper than the suite's bound, 1e-6 r,
  // and the energy never rises.
  for (const bool between_fixed_balls : {false, true}) {
    const Scene s = ball_driven_into_a_wedge(1e-12, between_fixed_balls);
    for (const Recorded& r : {run<double>(s, 1.0), run<Fixed>(s, 1.0)}) {
      INFO((between_fixed_balls ? "two fixed balls" : "floor and fixed ball"));
      CHECK(r.summary.deepest_overlap < 1e-6 * kPinchr);
      CHECK(std::fabs(r.frames.back().position[0]) > 0.4);  // left the wedge at x = 0, through or back
      check_energy_never_rises(r, r.frames.front().energy);
    }
  }
}

TEST_CASE("engine: a ball of restitution near 1 in a narrow wedge is turned back, not stopped", "[sim]") {
  // (Found by review.) A V at θ = 0.0015 from the vertical (α = 0.003), e =
  // 0.999: (1 + e) sin α = 6.0e-3 > 1 − e = 1e-3, so the series of strikes
  // at one instant always ends: the textbook series takes 1,062 strikes
  // and sends the ball back up at 0.588 of its speed. A rule that called
  // it a collapse after 2^10 strikes stopped the ball dead.
  const double theta = 0.0015;
  const double start = kPinchr / std::sin(theta) + 10;  // 10 above where it meets both walls
  const auto [s, expected] = ball_falling_into_a_v(theta, 400, start, 0.999, 400.0, 10.0);
  REQUIRE(expected > 0.5);
  for (const Recorded& r : {run<double>(s, 40.0), run<Fixed>(s, 40.0)}) {
    const FrameRecord& last = r.frames.back();
    CHECK(std::hypot(last.velocity[0], last.velocity[1]) == Approx(expected).epsilon(1e-6));
    CHECK(last.velocity[1] > 0);
    CHECK(r.summary.energy_removed_by_rest == 0);
  }
}
