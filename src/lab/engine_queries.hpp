// The time-of-impact queries the event engine itself asks, for `collide2d
// bench toi`: generated families say what a method costs on queries of a
// shape; these say what it costs on the mix a run actually makes (most pairs
// far apart or moving apart, walls met from the cells next to them, and the
// fresh start of every record time).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "collide2d/scene/scene.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d {

// The engine's mixes: "engine_gas" (a hard-disk gas of 1,000 discs at packing
// fraction 0.45, no gravity: quadratics only) and "engine_abound" (the
// built-in Abound scene: gravity, walls, fixed balls, the rest rules).
const std::vector<std::string>& engine_query_mixes();

// The scene behind a mix.
Scene engine_mix_scene(const std::string& mix);

// The first `count` queries (ball–ball and ball–wall, as asked: each ball's
// state at the prediction's start and the horizon to the next record time)
// that the strict event engine, analytic method, asks while running `scene`.
// Runs the scene again from the start as often as needed to gather them.
std::vector<ToiQuery> engine_queries(const Scene& scene, std::size_t count);

}  // namespace collide2d
