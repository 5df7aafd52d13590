// Watching for tunnelling: a ball's centre never touches a wall in a correct
// run (it stays at least one radius away, and goes round a wall's end, never
// through it). Between two of a ball's own events its centre moves on one
// parabola p + v τ + ½ a τ²; its signed distance to a wall's line,
// s(τ) = d × (p(τ) − w_a), is a quadratic in τ, and a root of s inside the
// piece whose foot lies on the segment is a centre on the wall: a missed
// contact. Pieces are checked at every event of the ball and at every frame,
// from the start the watch kept for each ball (restart, observe) or, where
// the engine says where a piece began, from that (check: a gas keeps no
// copy). Diagnostics only (doubles; nothing here feeds back into the run).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "collide2d/geometry/vec2.hpp"

namespace collide2d {

struct PathPoint {
  Vec2<double> position, velocity, acceleration;
  double time = 0;
};

class TunnellingWatch {
 public:
  explicit TunnellingWatch(std::vector<std::array<double, 4>> walls) : walls_(std::move(walls)) {
    for (const auto& w : walls_)
      boxes_.push_back({std::fmin(w[0], w[2]), std::fmin(w[1], w[3]), std::fmax(w[0], w[2]), std::fmax(w[1], w[3])});
  }

  // The state every ball starts its next piece from (at a frame or checkpoint).
  void restart(const std::vector<PathPoint>& points) {
    starts_.clear();
    accelerations_.clear();
    starts_.reserve(points.size());
    for (const PathPoint& p : points) starts_.push_back({p.position, p.velocity, p.time});
    for (std::size_t i = 0; i < points.size(); ++i) keep_acceleration(i, points[i].acceleration);
  }

  // Ball i is at `now` (after any response there): check the piece since its
  // last point, then start a new piece.
  void observe(std::size_t i, const PathPoint& now) {
    check_piece(start_of(i), now);
    starts_[i] = {now.position, now.velocity, now.time};
    keep_acceleration(i, now.acceleration);
  }

  // The piece from `from` to `now`, checked with nothing kept: for an engine
  // that says where each piece began (Collision::piece_start_a, _b). Of
  // `now` only the position and the time are read.
  void check(const PathPoint& from, const PathPoint& now) { check_piece(from, now); }

  std::int64_t crossings() const { return crossings_; }
  void set_crossings(std::int64_t n) { crossings_ = n; }

 private:
  std::vector<std::array<double, 4>> walls_;
  std::vector<std::array<double, 4>> boxes_;  // each wall's bounding box: x_lo, y_lo, x_hi, y_hi
  // Where each ball's present piece starts. Its acceleration is kept apart,
  // and only once some ball has one: a gas's balls never do, and then the
  // watch takes 40 bytes a ball, not 56.
  struct Start {
    Vec2<double> position, velocity;
    double time = 0;
  };
  std::vector<Start> starts_;
  std::vector<Vec2<double>> accelerations_;  // empty: every ball's is zero
  std::int64_t crossings_ = 0;

  PathPoint start_of(std::size_t i) const {
    const Start& s = starts_[i];
    return {s.position, s.velocity, accelerations_.empty() ? Vec2<double>{} : accelerations_[i], s.time};
  }
  void keep_acceleration(std::size_t i, const Vec2<double>& a) {
    if (accelerations_.empty()) {
      if (a.x == 0 && a.y == 0) return;
      accelerations_.assign(starts_.size(), Vec2<double>{});
    }
    accelerations_[i] = a;
  }

  void check_piece(const PathPoint& from, const PathPoint& to) {
    const double tau = to.time - from.time;
    if (!(tau > 0)) return;
    // A piece that does not end where its parabola says had a change of motion
    // the watch did not see (leaving a wall): its path is unknown, skip it.
    const Vec2<double> end = position_at(from.position, from.velocity, from.acceleration, tau);
    const double scale = 1 + std::fabs(to.position.x) + std::fabs(to.position.y);
    if (std::fabs(end.x - to.position.x) + std::fabs(end.y - to.position.y) > 1e-9 * scale) return;
    // The piece lies within the box of its chord widened by its sag,
    // |a| τ² / 8 per axis (p(s) − chord(s) = ½ a s (s − τ)), and by a margin
    // far above rounding; a wall whose box it misses cannot be crossed, and
    // most pieces of a large scene are far from every wall.
    const double sag_x = std::fabs(from.acceleration.x) * tau * tau / 8, sag_y = std::fabs(from.acceleration.y) * tau * tau / 8;
    const double margin = 1e-9 * (scale + std::fabs(from.position.x) + std::fabs(from.position.y));
    const double lo_x = std::fmin(from.position.x, to.position.x) - sag_x - margin;
    const double hi_x = std::fmax(from.position.x, to.position.x) + sag_x + margin;
    const double lo_y = std::fmin(from.position.y, to.position.y) - sag_y - margin;
    const double hi_y = std::fmax(from.position.y, to.position.y) + sag_y + margin;
    for (std::size_t k = 0; k < walls_.size(); ++k) {
      const auto& box = boxes_[k];
      if (hi_x < box[0] || box[2] < lo_x || hi_y < box[1] || box[3] < lo_y) continue;
      const auto& w = walls_[k];
      const Vec2<double> a{w[0], w[1]}, d{w[2] - w[0], w[3] - w[1]};
      // s(τ) = s0 + s1 τ + s2 τ²
      const double s0 = cross(d, from.position - a), s1 = cross(d, from.velocity), s2 = 0.5 * cross(d, from.acceleration);
      const Roots roots = roots_in(s0, s1, s2, tau);
      for (int k = 0; k < roots.count; ++k) {
        const double root = roots.at[k];
        const Vec2<double> p = position_at(from.position, from.velocity, from.acceleration, root);
        const double along = dot(d, p - a);
        if (along >= 0 && along <= length_squared(d)) ++crossings_;
      }
    }
  }

  struct Roots {
    std::array<double, 2> at{};
    int count = 0;
  };

  // Roots of s0 + s1 τ + s2 τ² in (0, tau] where s changes sign (at most two;
  // no allocation: this runs for every wall at every event).
  static Roots roots_in(double s0, double s1, double s2, double tau) {
    Roots roots;
    auto keep = [&](double r) {
      if (r > 0 && r <= tau) roots.at[static_cast<std::size_t>(roots.count++)] = r;
    };
    if (s2 == 0) {
      if (s1 != 0) keep(-s0 / s1);
      return roots;
    }
    const double disc = s1 * s1 - 4 * s2 * s0;
    if (!(disc > 0)) return roots;  // no crossing (a double root only touches)
    const double q = -0.5 * (s1 + std::copysign(std::sqrt(disc), s1));
    keep(q / s2);
    if (q != 0) keep(s0 / q);
    return roots;
  }
};

}  // namespace collide2d
