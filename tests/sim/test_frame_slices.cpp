// Frames handed on in slices (simulate.hpp's FrameSink, as `collide2d run`
// takes a large scene's): joined, the slices are the whole frames bit for
// bit, the records carry the same energy and hash, and the overlap check,
// which then reads each centre from its ball, finds the same deepest overlap.
// In both engines (a gas; Abound under gravity) and both number modes.
#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/scene/builtin_scene.hpp"
#include "collide2d/sim/simulate.hpp"
#include "engine_runs.hpp"
#include "lab/bench_scenes.hpp"

using namespace collide2d;

namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Takes the frames in slices of `k` balls and joins them again.
struct JoiningSink {
  std::size_t k;
  std::vector<FrameRecord>* frames;
  FrameRecord joined;
  std::size_t balls_per_slice() const { return k; }
  void slice(const FrameSlice& s) {
    REQUIRE(s.first == joined.position.size() / 2);  // in order, none left out
    joined.position.insert(joined.position.end(), s.position.begin(), s.position.end());
    joined.velocity.insert(joined.velocity.end(), s.velocity.begin(), s.velocity.end());
    joined.position_raw.insert(joined.position_raw.end(), s.position_raw.begin(), s.position_raw.end());
    joined.velocity_raw.insert(joined.velocity_raw.end(), s.velocity_raw.begin(), s.velocity_raw.end());
    joined.time = s.time;
  }
  void operator()(const FrameRecord& f) {
    if (k == 0) return frames->push_back(f);  // whole frames
    REQUIRE(f.position.empty());
    REQUIRE(same_bits(f.time, joined.time));
    FrameRecord whole = std::move(joined);
    joined = {};
    whole.step = f.step, whole.energy = f.energy, whole.state_hash = f.state_hash;
    frames->push_back(std::move(whole));
  }
};

template <class Num>
void check_slices_join(const Scene& s, double until, std::size_t k) {
  const test::Recorded whole = test::run<Num>(s, until);
  std::vector<FrameRecord> frames;
  std::vector<EventRecord> events;
  JoiningSink sink{k, &frames};
  const SimulationSummary sliced =
      simulate<Num>(s, until, sink, [&](const EventRecord& e) { events.push_back(e); });
  REQUIRE(frames.size() == whole.frames.size());
  REQUIRE(frames.size() >= 3);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    INFO("frame " << i);
    const FrameRecord &a = whole.frames[i], &b = frames[i];
    CHECK(a.step == b.step);
    CHECK(same_bits(a.time, b.time));
    CHECK(same_bits(a.position, b.position));
    CHECK(same_bits(a.velocity, b.velocity));
    CHECK(a.position_raw == b.position_raw);
    CHECK(a.velocity_raw == b.velocity_raw);
    CHECK(same_bits(a.energy, b.energy));
    CHECK(a.state_hash == b.state_hash);
  }
  CHECK(events.size() == whole.events.size());
  CHECK(sliced.final_hash == whole.summary.final_hash);
  CHECK(same_bits(sliced.deepest_overlap, whole.summary.deepest_overlap));
}

// A frame no larger than a slice goes whole, as to a plain callable.
struct WholeFramesSink {
  std::size_t k;
  int* whole_frames;
  std::size_t balls_per_slice() const { return k; }
  void slice(const FrameSlice&) { FAIL("a frame of at most one slice was sliced"); }
  void operator()(const FrameRecord& f) { *whole_frames += !f.position.empty(); }
};

}  // namespace

TEST_CASE("frames in slices: a gas's join into its whole frames, in both modes", "[sim]") {
  const Scene gas = hard_disk_gas(60, 0.3, 1, 2, 10);
  for (std::size_t k : {1, 7, 59}) {
    INFO(k << " balls a slice");
    check_slices_join<double>(gas, 2, k);
    check_slices_join<Fixed>(gas, 2, k);
  }
}

TEST_CASE("frames in slices: Abound's (gravity, the general engine) join too", "[sim]") {
  const Scene abound = scene_from_text(builtin_abound_scene_json());
  check_slices_join<double>(abound, 3, 2);
  check_slices_join<Fixed>(abound, 3, 2);
}

TEST_CASE("frames in slices: a frame no larger than a slice is whole", "[sim]") {
  const Scene gas = hard_disk_gas(20, 0.3, 1, 1, 5);
  for (std::size_t k : {0, 20, 1000}) {
    int whole_frames = 0;
    const SimulationSummary s = simulate<double>(gas, 1, WholeFramesSink{k, &whole_frames}, [](const EventRecord&) {});
    CHECK(whole_frames == s.frames);
  }
}

// The deepest overlaps of shipped runs (60 simulated seconds) as the
// whole-frame check found them (every wall's box widened by the largest
// radius; `collide2d run X.json --until 60 [--mode fixed]`, the summary's
// deepest_overlap; first stored at 8a7dae3, stored again when the rest
// rules of 2026-12-07 changed these histories, Abound's fixed one when the
// island eliminations kept only their upper triangle; the funnel's strict
// one changed when an impact's slow partings were held as the pivoting met
// them and came back when a plastic re-do restored the contacts its
// elastic trial had removed, and again when a jam came to join the touching
// pairs of every ball struck at its instant): the check of slices, which reads each centre from its ball, finds
// the same doubles. Abound has five radii and walls at three slopes, the
// funnel slanted walls.
TEST_CASE("frames in slices: the deepest overlaps of the whole-frame check, stored", "[sim]") {
  struct Stored {
    const char* scene;
    double strict, fixed;
  };
  for (const Stored& s : {Stored{"abound", 6.661338147750939e-16, 8.881784197001252e-16},
                          Stored{"funnel", 9.298117831235686e-16, 1.8041124150158794e-16}}) {
    INFO(s.scene);
    const Scene scene = load_scene_file(std::string(COLLIDE2D_SCENES_DIR) + "/" + s.scene + ".json");
    for (std::size_t k : {std::size_t{0}, std::size_t{7}}) {
      INFO(k << " balls a slice (0: whole frames)");
      std::vector<FrameRecord> frames;
      const SimulationSummary strict = simulate<double>(scene, 60, JoiningSink{k, &frames}, [](const EventRecord&) {});
      const SimulationSummary fixed = simulate<Fixed>(scene, 60, JoiningSink{k, &frames}, [](const EventRecord&) {});
      CHECK(same_bits(strict.deepest_overlap, s.strict));
      CHECK(same_bits(fixed.deepest_overlap, s.fixed));
    }
  }
}
