// The named scenes of the benchmarks (collide2d bench sim, bench peers): a
// hard-disk gas of any size and density, and the shipped settling scenes.
#pragma once

#include <cstdint>
#include <string>

#include "collide2d/scene/scene.hpp"

namespace collide2d {

// N equal discs (radius 0.5, mass 1, restitution 1) at packing fraction
// eta = N π r² / L² in a square box of four walls, side L, no gravity. They
// start on a square lattice (spacing L / ceil(sqrt N), at most eta = π/4
// without overlap), each at `speed` in a direction drawn from `seed`.
// Records `frames` frames over `duration`.
Scene hard_disk_gas(std::int64_t n, double eta, double speed, double duration, int frames, std::uint64_t seed = 2026);

// Collisions per unit time of a hard-disk gas (ball–ball, the whole gas), to
// size a run: Enskog's frequency per disc ω = 2σ n g(σ) sqrt(π kT / m)
// (σ = 2r the diameter, n = N/L², kT/m = speed²/2 in two dimensions), with
// Henderson's contact value g(σ) = (1 − 7η/16) / (1 − η)². An estimate: the
// benchmark reports what it measures.
double hard_disk_collision_rate(std::int64_t n, double eta, double speed);

}  // namespace collide2d
