// The same seed generates the same scenes on every machine.
//
// A generator that draws twice in one expression (two arguments of a call,
// two operands of ×) leaves the order of the draws to the compiler: gcc takes
// a call's arguments last first on x86-64 and first first on aarch64, and
// there the property suite ran other scenes than here (issue 15: the
// article's formula, expected to fail, found no counterexample on aarch64).
// This hashes the scenes each generator makes from fixed seeds at every size
// and compares with the hash x86-64 gives; `ctest --preset cross-aarch64`
// (and the others) run it under qemu. A generator changed on purpose
// changes the hash: the failing check shows the new one (in decimal).
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

#include "collide2d/sim/simulate.hpp"
#include "scene_generators.hpp"

namespace {

std::uint64_t fnv1a(std::uint64_t h, const std::string& text) {
  collide2d::hash_bytes(h, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  return h;
}

// `cases` scenes (or discards) of `gen`, at sizes 0..99, from seeds 1..cases.
template <class Gen, class Text>
std::uint64_t hash_of_generated(const Gen& gen, int cases, Text text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (int k = 0; k < cases; ++k) {
    const rc::Random random(static_cast<std::uint64_t>(k) + 1);
    try {
      h = fnv1a(h, text(gen(random, k % 100).value()));
    } catch (...) {  // RC_PRE in the generator: a discard, the same everywhere
      h = fnv1a(h, "discard");
    }
  }
  return h;
}

}  // namespace

using namespace collide2d;
using namespace collide2d::properties;

TEST_CASE("generated scenes are the same bits on every machine", "[.generation]") {
  auto json = [](const Scene& s) { return scene_to_json(s, -1); };
  auto scene_json = [&](const GeneratedScene& g) { return json(g.scene); };
  const SceneOptions general{}, elastic{.elastic = true, .hard_cases = false, .wide = false},
      fixed{.fixed_mode = true};
  const std::uint64_t h[] = {
      hash_of_generated(valid_scene(general), 300, scene_json),
      hash_of_generated(valid_scene(elastic), 300, scene_json),
      hash_of_generated(valid_scene(fixed), 300, scene_json),
      hash_of_generated(pile_scene(), 100, [&](const GeneratedPile& p) { return json(p.scene); }),
      hash_of_generated(bounce_scene(), 100, json),
      hash_of_generated(struck_sleeper_scene(), 100, json),
  };
  CHECK(h[0] == 0xba957e6fd5f01338ULL);
  CHECK(h[1] == 0x25474cb6f7a1d06eULL);
  CHECK(h[2] == 0x13ecddd762a9a7c4ULL);
  CHECK(h[3] == 0x7ae14237f4f62940ULL);
  CHECK(h[4] == 0xadd47565ed58a793ULL);
  CHECK(h[5] == 0xff5fb68f5cdfdb3fULL);
}
