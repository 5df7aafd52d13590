// The scene properties (scene_checks.hpp) over generated scenes
// (scene_generators.hpp), run by check_property (property_runner.hpp): a
// failure leaves its shrunk scene in the regressions directory.
//
// CI size (RapidCheck's default 100 cases, max_size 100): at most 9 balls in
// the random family, durations ≤ 1 s (fixed-matches-strict: ≤ 1/4 s); piles:
// 20 cases of at most 22 balls.
#include <catch2/catch.hpp>
#include <rapidcheck.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "collide2d/response/response.hpp"
#include "property_runner.hpp"
#include "scene_checks.hpp"
#include "scene_generators.hpp"
#include "scene_json.hpp"

using namespace collide2d;
using namespace collide2d::properties;

namespace {

// Runs a check on a scene; a check that does not apply to it (NotApplicable,
// scene_checks.hpp) discards the case: neither a pass nor a failure.
CheckResult run_check(const NamedCheck& check, const Scene& scene, const std::string& mode) {
  try {
    return check.check(scene, mode, scene.duration);
  } catch (const NotApplicable& e) {
    discard_not_applicable(e.what());
  }
}

// Runs the named check on generated scenes; a failing scene is remembered
// (the last one remembered is the shrunk counterexample).
void scene_property(const std::string& slug, const std::string& mode, SceneOptions options, double max_duration = 0,
                    Expect expect = Expect::pass) {
  const NamedCheck* check = find_check(slug);
  REQUIRE(check != nullptr);
  options.fixed_mode = mode != "strict";
  check_property(check->property, mode, [=] {
    const GeneratedScene generated = *valid_scene(options);
    tag_features(generated);
    Scene scene = generated.scene;
    if (max_duration > 0) {
      scene.duration = std::min(scene.duration, max_duration);
      scene.record_interval = std::min(scene.record_interval, scene.duration);
    }
    if (const CheckResult failure = run_check(*check, scene, mode)) {
      last_failing_scene() = FailingScene{scene, slug, scene.duration};
      RC_FAIL(*failure);
    }
  }, expect);
}

const char* modes[] = {"strict", "fixed"};

// The pile properties (rest_checks.cpp) over generated piles
// (scene_generators.hpp), run to the scene's duration, T_rest + 2 s. They
// take a fifth of the cases RC_PARAMS asks for (20 at CI size): a pile run
// is long (minutes of simulated time; seconds of wall time where the engine
// never lets the pile rest and the run is stopped by its event budget).
constexpr int pile_case_share = 5;

// Runs the named check on the scenes `make` returns (it draws them from a
// generator and tags them); a failing scene is remembered. `share`: the
// fraction 1/share of RapidCheck's cases this property takes.
template <class Make>
void generated_property(const std::string& slug, const std::string& mode, Make make, int share = 1) {
  const NamedCheck* check = find_check(slug);
  REQUIRE(check != nullptr);
  check_property(check->property, mode, [=] {
    const Scene scene = make();
    if (const CheckResult failure = run_check(*check, scene, mode)) {
      last_failing_scene() = FailingScene{scene, slug, scene.duration};
      RC_FAIL(*failure);
    }
  }, Expect::pass, share);
}

void pile_property(const std::string& slug, const std::string& mode) {
  generated_property(slug, mode, [] {
    const GeneratedPile generated = *pile_scene();
    tag_pile_features(generated);
    return generated.scene;
  }, pile_case_share);
}

}  // namespace

TEST_CASE("scene properties: energy is kept in elastic scenes", "[scene][property]") {
  for (const char* mode : modes) scene_property("energy-kept", mode, {.elastic = true});
}

TEST_CASE("scene properties: ball-ball collisions keep momentum", "[scene][property]") {
  for (const char* mode : modes) scene_property("momentum-kept", mode, {});
}

// Every impulse, whichever rule applied it (impulse_checks.cpp): the rest
// rules act in the resting family, in gravity boxes with restitutions below
// 1 and in crowds.
TEST_CASE("scene properties: every impulse keeps momentum but for what supports push", "[scene][property]") {
  for (const char* mode : modes) scene_property("impulses-keep-momentum", mode, {});
}

TEST_CASE("scene properties: the article's two-ball formula breaks momentum (expected counterexample)", "[scene][property]") {
  // Elastic (every restitution 1), so the counterexample must be unequal
  // masses (the formula also breaks for unequal restitutions); no hard cases:
  // a plain box of a few balls is all it needs.
  scene_property("article-momentum-kept", "strict", {.elastic = true, .hard_cases = false, .wide = false}, 0, Expect::counterexample);
}

TEST_CASE("scene properties: reflections keep speed and restitution scales the normal speed", "[scene][property]") {
  for (const char* mode : modes) scene_property("reflection-speed", mode, {});
}

TEST_CASE("scene properties: no overlap and no tunnelling on the continuous motion", "[scene][property]") {
  for (const char* mode : modes) scene_property("no-overlap", mode, {});
}

TEST_CASE("scene properties: the same scene gives the same bits", "[scene][property]") {
  for (const char* mode : modes) scene_property("deterministic", mode, {});
}

TEST_CASE("scene properties: a run file replays bit for bit", "[scene][property]") {
  for (const char* mode : modes) scene_property("run-file-replay", mode, {});
}

TEST_CASE("scene properties: resume from a checkpoint equals the uninterrupted run", "[scene][property]") {
  for (const char* mode : modes) scene_property("resume", mode, {});
}

TEST_CASE("scene properties: fixed and strict agree on short horizons", "[scene][property]") {
  scene_property("fixed-matches-strict", "both", {.elastic = true, .wide = false}, 0.25);
}

// Every restitution below 1 (the scene's default too): the general families,
// scaled and translated as everywhere (fixed mode discards the scenes whose
// balls are too small for its normals to round within the claim).
TEST_CASE("scene properties: energy never rises where every restitution is below 1", "[scene][property]") {
  for (const char* mode : modes) scene_property("energy-never-rises", mode, {.dissipative = true});
}

TEST_CASE("pile properties: energy never rises while a pile settles", "[pile][property]") {
  for (const char* mode : modes) pile_property("energy-never-rises", mode);
}

TEST_CASE("pile properties: a pile comes to rest within T_rest and does not overlap", "[pile][property]") {
  for (const char* mode : modes) pile_property("pile-comes-to-rest", mode);
}

TEST_CASE("pile properties: a ball dropped on a resting pile wakes it with momentum kept", "[pile][property]") {
  for (const char* mode : modes) pile_property("wake-keeps-momentum", mode);
}

// A ball dropped on a floor comes to rest when the README's default rest
// height says (bounce_checks.cpp): the rest rules' scales are checked
// against the documented contract, not against themselves.
TEST_CASE("bounce properties: a bouncing ball comes to rest where the documented rest height says", "[scene][property]") {
  for (const char* mode : modes)
    generated_property("bounce-comes-to-rest-on-time", mode, [] {
      const Scene scene = *bounce_scene();
      RC_TAG(scene.balls[0].restitution < 0.6 ? "e < 0.6" : scene.balls[0].restitution < 0.85 ? "e 0.6-0.85" : "e >= 0.85");
      return scene;
    });
}

// The smallest wake-up (bounce_checks.cpp): a ball lying on a floor, struck
// by one dropped on it, moves, with the pair's horizontal momentum kept.
TEST_CASE("bounce properties: a ball struck while lying on a floor moves, with momentum kept", "[scene][property]") {
  for (const char* mode : modes)
    generated_property("struck-sleeper-keeps-momentum", mode, [] {
      const Scene scene = *struck_sleeper_scene();
      RC_TAG(scene.balls[0].mass == scene.balls[1].mass ? "equal masses" : "unequal masses");
      return scene;
    });
}

// The response formulas themselves over generated inputs: velocities,
// masses (k/4, 1/4 to 16), a unit normal from a small-integer direction, and
// restitutions. The impulse response keeps momentum (bound as in
// physics_checks.cpp: 8 eps Σ m(|v| + |v'|)); the article's does not for
// unequal masses: RapidCheck must find that.
namespace {
template <class Response>
void response_keeps_momentum(Response response) {
  auto speed = [] { return *rc::gen::inRange(-640, 641) / 64.0; };
  const Vec2<double> v1{speed(), speed()}, v2{speed(), speed()};
  const double m1 = *rc::gen::inRange(1, 65) / 4.0, m2 = *rc::gen::inRange(1, 65) / 4.0;
  const Vec2<double> d{static_cast<double>(*rc::gen::inRange(-16, 17)), static_cast<double>(*rc::gen::inRange(-16, 17))};
  RC_PRE(!(d == Vec2<double>{}));
  const Vec2<double> n = normalized(d);
  const double e1 = 1 - *rc::gen::inRange(0, 65) / 64.0, e2 = 1 - *rc::gen::inRange(0, 65) / 64.0;
  const TwoBallVelocities<double> out = response(v1, v2, m1, m2, n, e1, e2);
  const double px = m1 * (out.v1.x - v1.x) + m2 * (out.v2.x - v2.x), py = m1 * (out.v1.y - v1.y) + m2 * (out.v2.y - v2.y);
  const double size = m1 * (length(v1) + length(out.v1)) + m2 * (length(v2) + length(out.v2));
  RC_LOG() << "m1 " << m1 << " m2 " << m2 << " e1 " << e1 << " e2 " << e2 << " momentum change " << std::hypot(px, py) << "\n";
  RC_ASSERT(std::hypot(px, py) <= 8 * std::numeric_limits<double>::epsilon() * size);
}
}  // namespace

TEST_CASE("response properties: the impulse response keeps momentum and the article formula does not", "[response][property]") {
  check_property("two_ball_impulse_response keeps momentum", "strict", [] {
    response_keeps_momentum([](auto v1, auto v2, double m1, double m2, auto n, double e1, double e2) {
      return two_ball_impulse_response(v1, v2, m1, m2, n, e1 * e2);
    });
  });
  check_property("article_two_ball_response keeps momentum", "strict", [] {
    response_keeps_momentum([](auto v1, auto v2, double m1, double m2, auto n, double e1, double e2) {
      return article_two_ball_response(v1, v2, m1, m2, n, e1, e2);
    });
  }, Expect::counterexample);
}

// Hidden (not run by ctest): one scene file through one check, for a look at
// a counterexample by hand:
//   COLLIDE2D_CHECK=no-overlap COLLIDE2D_MODE=strict COLLIDE2D_SCENE=file.json \
//     build/release/properties/collide2d_scene_properties "[.replay]"
TEST_CASE("replay one scene file through one check", "[.replay]") {
  const char* slug = std::getenv("COLLIDE2D_CHECK");
  const char* mode = std::getenv("COLLIDE2D_MODE");
  const char* file = std::getenv("COLLIDE2D_SCENE");
  if (slug == nullptr || file == nullptr) {
    WARN("replay: set COLLIDE2D_CHECK and COLLIDE2D_SCENE (and COLLIDE2D_MODE) to replay a file; nothing to do");
    return;
  }
  const NamedCheck* check = find_check(slug);
  REQUIRE(check != nullptr);
  const Scene scene = load_scene_file(file);
  try {
    const CheckResult r = check->check(scene, mode ? mode : "strict", scene.duration);
    std::cout << slug << ": " << r.value_or("holds") << "\n";
  } catch (const NotApplicable& e) {
    std::cout << slug << ": not applicable: " << e.what() << "\n";
  }
}
