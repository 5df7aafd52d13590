// The built-in Abound scene (datasets/scenes/abound.json, compiled in): a
// 16 × 12 box of walls with restitution 0.9, three fixed balls and twenty
// balls of radius 0.3 to 0.45 under gravity, restitution 0.9, for 20 s.
#pragma once

namespace collide2d {

const char* builtin_abound_scene_json();

}  // namespace collide2d
