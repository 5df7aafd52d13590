// The built-in scenes, compiled in from datasets/scenes/:
//  - Abound (abound.json), the default of `collide2d run`: a 16 × 12 box of
//    walls with restitution 0.9, three fixed balls and twenty balls of radius
//    0.3 to 0.45 under gravity, restitution 0.9, for 20 s;
//  - the settling pile of the benchmarks (pile_50.json): 50 balls of two
//    sizes, restitution 0.9, dropped into a box with one slanted wall, 60 s.
#pragma once

namespace collide2d {

const char* builtin_abound_scene_json();
const char* builtin_pile_scene_json();

}  // namespace collide2d
