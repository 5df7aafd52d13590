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

// Reports the scene's features (family, gravity, number of balls, fixed
// balls, transformed) with RC_TAG: call it inside the property (tags set
// inside a generator are not counted).
void tag_features(const GeneratedScene& generated);

}  // namespace collide2d::properties
