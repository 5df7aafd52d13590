// RapidCheck generators of valid scenes (no overlap at t = 0, as
// check_no_initial_overlap demands). Built from rc::gen combinators picking
// small integers, scaled by powers of two, so failing scenes shrink towards
// fewer balls and walls and rounder numbers (1/64 multiples, 0, 1).
#pragma once

#include <ostream>
#include <string>

#include <rapidcheck.h>

#include "scene/scene.hpp"

namespace collide2d::properties {

struct SceneOptions {
  bool elastic = false;      // every restitution 1 (energy property)
  bool dissipative = false;  // every restitution below 1, the scene's default too (energy-never-rises)
  bool fixed_mode = false;   // keep numbers inside what Q63.64 handles (see .cpp)
  bool hard_cases = true;    // mix in the hard-case families
  bool wide = true;          // scale by 2^e and translate by up to 2^30 (2^20 fixed)
};

// Families, reported through RC_TAG by the properties: "random" (a box,
// segments or a funnel, balls on a jittered grid), "grazing", "simultaneous",
// "resting", "fast".
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

// Reports the scene's features (family, gravity, number of balls, fixed
// balls, transformed) with RC_TAG: call it inside the property (tags set
// inside a generator are not counted).
void tag_features(const GeneratedScene& generated);

}  // namespace collide2d::properties
