#include "lab/bench_scenes.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace collide2d {

namespace {
constexpr double gas_radius = 0.5;

double box_side(std::int64_t n, double eta) {
  return std::sqrt(static_cast<double>(n) * std::numbers::pi * gas_radius * gas_radius / eta);
}
}  // namespace

Scene hard_disk_gas(std::int64_t n, double eta, double speed, double duration, int frames, std::uint64_t seed) {
  Scene s;
  s.name = "gas_" + std::to_string(n) + "_eta" + std::to_string(eta).substr(0, 4);
  s.duration = duration;
  s.restitution = 1;
  s.record_interval = duration / frames;
  const double L = box_side(n, eta);
  s.walls = {{{0, 0}, {L, 0}, 1}, {{L, 0}, {L, L}, 1}, {{L, L}, {0, L}, 1}, {{0, L}, {0, 0}, 1}};
  const auto per_row = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double spacing = L / static_cast<double>(per_row);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
  s.balls.reserve(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) {
    const double phi = angle(rng);
    BallSpec b;
    b.position = {(static_cast<double>(k % per_row) + 0.5) * spacing, (static_cast<double>(k / per_row) + 0.5) * spacing};
    b.velocity = {speed * std::cos(phi), speed * std::sin(phi)};
    b.radius = gas_radius;
    s.balls.push_back(b);
  }
  return s;
}

double hard_disk_collision_rate(std::int64_t n, double eta, double speed) {
  const double L = box_side(n, eta);
  const double density = static_cast<double>(n) / (L * L);
  const double contact = (1 - 7 * eta / 16) / ((1 - eta) * (1 - eta));
  const double per_disc = 2 * (2 * gas_radius) * density * contact * std::sqrt(std::numbers::pi * speed * speed / 2);
  return static_cast<double>(n) * per_disc / 2;
}

}  // namespace collide2d
