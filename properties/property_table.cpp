#include "property_table.hpp"

#include <algorithm>
#include <stdexcept>

#include <rapidcheck.h>

#include "property_case.hpp"
#include "scene_checks.hpp"
#include "scene_generators.hpp"

namespace collide2d::properties {
namespace {

const NamedCheck& check_of(const std::string& slug) {
  const NamedCheck* check = find_check(slug);
  if (check == nullptr) throw std::logic_error("no scene check named " + slug);
  return *check;
}

// Runs a check on a scene; a check that does not apply to it (NotApplicable)
// discards the case: neither a pass nor a failure. A failing scene is
// remembered (shrinking ends on the last failing candidate, so the scene
// remembered last is the shrunk counterexample).
void judge(const NamedCheck& check, const Scene& scene, const std::string& mode) {
  last_generated_scene_balls() = static_cast<int>(scene.balls.size());
  CheckResult failure;
  try {
    failure = check.check(scene, mode, scene.duration);
  } catch (const NotApplicable& e) {
    discard_not_applicable(e.what());
  }
  if (failure) {
    last_failing_scene() = FailingScene{scene, check.slug, scene.duration};
    RC_FAIL(*failure);
  }
}

// The general families (valid_scene), durations capped at `max_duration`
// when it is positive.
SceneProperty general(const std::string& slug, const std::string& test_case, std::vector<std::string> modes,
                      SceneOptions options, double max_duration = 0, bool expect_counterexample = false) {
  const NamedCheck& check = check_of(slug);
  SceneProperty p{slug, test_case, check.property, std::move(modes), expect_counterexample, false, 1, {}};
  p.testable = [&check, options, max_duration](const std::string& mode) -> std::function<void()> {
    SceneOptions o = options;
    o.fixed_mode = mode != "strict";
    return [&check, o, max_duration, mode] {
      const GeneratedScene generated = *valid_scene(o);
      tag_features(generated);
      Scene scene = generated.scene;
      if (max_duration > 0) {
        scene.duration = std::min(scene.duration, max_duration);
        scene.record_interval = std::min(scene.record_interval, scene.duration);
      }
      judge(check, scene, mode);
    };
  };
  return p;
}

// Scenes from a generator of their own (piles, a bouncing ball, ...).
template <class Make>
SceneProperty generated(const std::string& slug, const std::string& test_case, Make make, bool open = false,
                        int case_share = 1) {
  const NamedCheck& check = check_of(slug);
  SceneProperty p{slug, test_case, check.property, {"strict", "fixed"}, false, open, case_share, {}};
  p.testable = [&check, make](const std::string& mode) -> std::function<void()> {
    return [&check, make, mode] { judge(check, make(), mode); };
  };
  return p;
}

Scene make_pile() {
  const GeneratedPile generated = *pile_scene();
  tag_pile_features(generated);
  return generated.scene;
}

Scene make_bounce() {
  const Scene scene = *bounce_scene();
  RC_TAG(scene.balls[0].restitution < 0.6 ? "e < 0.6" : scene.balls[0].restitution < 0.85 ? "e 0.6-0.85" : "e >= 0.85");
  return scene;
}

Scene make_struck_sleeper() {
  const Scene scene = *struck_sleeper_scene();
  RC_TAG(scene.balls[0].mass == scene.balls[1].mass ? "equal masses" : "unequal masses");
  return scene;
}

// Dense gases for the gas engine: a fifth of the cases too (four runs of
// up to 150 balls each).
Scene make_dense_gas() { return *dense_gas_scene(); }

// The pile properties take a fifth of the cases RC_PARAMS asks for (20 at CI
// size): a pile run is long (minutes of simulated time; seconds of wall time
// where the engine never lets the pile rest and its event budget stops it).
constexpr int pile_case_share = 5;

std::vector<SceneProperty> make_table() {
  const std::vector<std::string> both_modes{"strict", "fixed"};
  std::vector<SceneProperty> t;
  t.push_back(general("energy-kept", "scene properties: energy is kept in elastic scenes", both_modes, {.elastic = true}));
  t.push_back(general("momentum-kept", "scene properties: ball-ball collisions keep momentum", both_modes, {}));
  // Every impulse, whichever rule applied it (impulse_checks.cpp): the rest
  // rules act in the resting family, in gravity boxes with restitutions
  // below 1 and in crowds.
  t.push_back(general("impulses-keep-momentum", "scene properties: every impulse keeps momentum but for what supports push",
                      both_modes, {}));
  // Elastic (every restitution 1), so the counterexample must be unequal
  // masses (the formula also breaks for unequal restitutions); no hard
  // cases: a plain box of a few balls is all it needs.
  t.push_back(general("article-momentum-kept",
                      "scene properties: the article's two-ball formula breaks momentum (expected counterexample)", {"strict"},
                      {.elastic = true, .hard_cases = false, .wide = false}, 0, true));
  t.push_back(general("reflection-speed", "scene properties: reflections keep speed and restitution scales the normal speed",
                      both_modes, {}));
  t.push_back(general("no-overlap", "scene properties: no overlap and no tunnelling on the continuous motion", both_modes, {}));
  t.push_back(general("deterministic", "scene properties: the same scene gives the same bits", both_modes, {}));
  t.push_back(general("run-file-replay", "scene properties: a run file replays bit for bit", both_modes, {}));
  t.push_back(general("resume", "scene properties: resume from a checkpoint equals the uninterrupted run", both_modes, {}));
  // Gases (no accelerations) of every family, with every restitution and
  // fixed balls, so that jams and creeping send some strikes down the
  // general path in the middle of a run of plain ones.
  t.push_back(general("gas-fast-path", "scene properties: in a gas the plain gas path gives the general path's bits",
                      both_modes, {.gas = true}));
  // The same check over dense gases (scene_generators.cpp), where the gas
  // engine's stale contacts, crossings and jams come in every order: the
  // general families' gases are small, and few of their contacts go stale.
  t.push_back(generated("gas-fast-path", "gas properties: a dense gas gives the event engine's bits in the gas engine",
                        make_dense_gas, false, pile_case_share));
  t.back().slug = "dense-gas-fast-path";
  t.push_back(general("fixed-matches-strict", "scene properties: fixed and strict agree on short horizons", {"both"},
                      {.elastic = true, .wide = false}, 0.25));
  // Every restitution below 1 (the scene's default too): the general
  // families, scaled and translated as everywhere (fixed mode discards the
  // scenes whose balls are too small for its normals to round within the
  // claim).
  t.push_back(general("energy-never-rises", "scene properties: energy never rises where every restitution is below 1",
                      both_modes, {.dissipative = true}));
  t.push_back(generated("energy-never-rises", "pile properties: energy never rises while a pile settles", make_pile, true,
                        pile_case_share));
  t.back().slug = "pile-energy-never-rises";  // the same check as the row above, over piles
  t.push_back(generated("pile-comes-to-rest", "pile properties: a pile comes to rest within T_rest and does not overlap",
                        make_pile, true, pile_case_share));
  t.push_back(generated("wake-keeps-momentum", "pile properties: a ball dropped on a resting pile wakes it with momentum kept",
                        make_pile, true, pile_case_share));
  // A ball dropped on a floor comes to rest when the README's default rest
  // height says (bounce_checks.cpp): the rest rules' scales are checked
  // against the documented contract, not against themselves.
  t.push_back(generated("bounce-comes-to-rest-on-time",
                        "bounce properties: a bouncing ball comes to rest where the documented rest height says", make_bounce));
  // The smallest wake-up (bounce_checks.cpp): a ball lying on a floor,
  // struck by one dropped on it, moves, with the pair's horizontal momentum
  // kept.
  t.push_back(generated("struck-sleeper-keeps-momentum",
                        "bounce properties: a ball struck while lying on a floor moves, with momentum kept",
                        make_struck_sleeper));
  return t;
}

}  // namespace

const std::vector<SceneProperty>& scene_property_table() {
  static const std::vector<SceneProperty> table = make_table();
  return table;
}

const SceneProperty* find_scene_property(const std::string& slug) {
  for (const SceneProperty& p : scene_property_table())
    if (p.slug == slug) return &p;
  return nullptr;
}

int& last_generated_scene_balls() {
  thread_local int balls = 0;
  return balls;
}

}  // namespace collide2d::properties
