// RapidCheck generators of valid scenes (no overlap at t = 0, as
// check_no_initial_overlap demands). Built from rc::gen combinators picking
// small integers, scaled by powers of two, so failing scenes shrink towards
// fewer balls and walls and rounder numbers (1/64 multiples, 0, 1).
#pragma once

#include <ostream>
#include <string>

#include <rapidcheck.h>

#include "collide2d/scene/scene.hpp"

namespace collide2d::properties {

struct SceneOptions {
  bool elastic = false;      // every restitution 1 (energy property)
  bool dissipative = false;  // every restitution below 1, the scene's default too (energy-never-rises)
  bool fixed_mode = false;   // keep numbers inside what Q63.64 handles (see .cpp)
  bool hard_cases = true;    // mix in the hard-case families and crowds
  bool wide = true;          // scale by 2^e and translate by up to 2^30 (2^20 fixed)
  bool gas = false;          // no gravity and no ball's own acceleration (the engine's gas paths)
};

// Families, reported through RC_TAG by the properties: "random" (a box,
// segments or a funnel, balls on a jittered grid), "grazing", "simultaneous",
// "resting", "fast", "crowd" (the random family's box with 30 to 200 balls),
// "cradle" (gases only: a row of touching balls struck against a wall).
const char* family_name(int family);

struct GeneratedScene {
  Scene scene;
  int family = 0;
  bool transformed = false;  // scaled by 2^e and/or translated
};
void showValue(const GeneratedScene& generated, std::ostream& os);

// A valid scene of a random family.
rc::Gen<GeneratedScene> valid_scene(SceneOptions options);

// A pile (rest_checks.cpp, scene_generators.cpp): 10 to 10 + size/8 balls
// (at most 200; CI's max_size 100 gives at most 22) of 1–3 kinds (radius,
// mass, restitution 0.30–0.95), poured from a loose grid into a closed box
// whose floor is one slanted wall or two (a V), under gravity (0, −g). Its
// duration is T_rest + 2 s (pile_bounds). Shrinks towards 10 balls of one
// kind, the least bouncy.
struct GeneratedPile {
  Scene scene;
  int shape = 0;  // 0 floor down to the right, 1 down to the left, 2 a V
  int kinds = 1;
};
void showValue(const GeneratedPile& generated, std::ostream& os);
rc::Gen<GeneratedPile> pile_scene();
void tag_pile_features(const GeneratedPile& generated);

// A ball dropped on a floor (bounce_checks.cpp): radius k/64 (k 4–16),
// restitution k/128 (k 39–121) on a wall of restitution 1, from rest at a
// height k/16 (k 1–32) of its lowest point above the wall y = 0 (x from −1
// to 1), gravity (0, −g), g = k/4 (k 4–80). No rest settings: the default
// rest height is what is checked. Duration: the series' end plus 1 s.
rc::Gen<Scene> bounce_scene();
// Ball 0 lying on the wall y = 0 (x from −2 to 2), ball 1 dropped from rest
// onto it from k/16 (k 8–32) above its top, off centre by k/64 of the
// contact distance (|k| 1–56, both sides): radii k/64 (k 4–16), masses
// 1 + k/4 (k 0–12), restitutions k/128 (k 39–121), the wall's too; gravity
// (0, −g), g = k/4 (k 4–80). Duration: the fall plus 1 s.
rc::Gen<Scene> struck_sleeper_scene();

// A dense gas in a box, a jam in a third of the cases (scene_generators.cpp).
rc::Gen<Scene> dense_gas_scene();

// Reports the scene's features (family, gravity, number of balls, fixed
// balls, transformed) with RC_TAG: call it inside the property (tags set
// inside a generator are not counted).
void tag_features(const GeneratedScene& generated);

}  // namespace collide2d::properties
