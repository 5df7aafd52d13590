// The stored answers and hashes, judged by an oracle rather than by the code
// that wrote them. The tests that regenerate them (cli.toi_determinism_*,
// cli.hardset_regenerates, cli.run_replay_*) compare the code's output with
// the stored file, bit for bit: a bug that changes the output fails them,
// and whoever regenerates the file to make them pass again would bless the
// bug. These tests fail on such a file however it was made:
//  - datasets/determinism/answers_{strict,fixed}.csv, collide2d toi's
//    answers to queries.jsonl: every answer meets the acceptance rule
//    against the 60-digit oracle (lab/oracle.hpp) within the method's stated
//    bound: 1e-12 of the query's scale strict, the bound derived from the
//    Q63.64 format fixed (properties/fixed_toi_bound.hpp);
//  - datasets/hard/hard_queries.jsonl, the oracle's own answers: each is
//    checked by another route than the one that found it (the gap evaluated
//    at the stored time, the stored scale recomputed, the minimum gap
//    against the gap each query was built to have);
//  - datasets/determinism/*.hash, the final state hashes of whole runs: the
//    run that gives the hash obeys the physics checks of the property suite
//    (properties/scene_checks.hpp: no overlap, momentum, reflections,
//    impulses, energy where the scene is elastic), a hash being only as good
//    as the run behind it. The dense gas (50 s, 400 balls) is the slow part:
//    a test of its own, label "slow" (tests/CMakeLists.txt).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "collide2d/scene/query_parse.hpp"
#include "fixed_toi_bound.hpp"
#include "lab/oracle.hpp"
#include "scene_checks.hpp"

using namespace collide2d;
using namespace collide2d::properties;
namespace fs = std::filesystem;

namespace {

const fs::path datasets = COLLIDE2D_DATASETS_DIR;

std::vector<nlohmann::json> json_lines(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<nlohmann::json> lines;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

struct StoredAnswer {
  bool hit = false;
  double t = 0;
};

// index,hit,t with t empty for a miss (collide2d toi's CSV).
std::vector<StoredAnswer> answers(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "index,hit,t");
  std::vector<StoredAnswer> out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream fields(line);
    std::string index, hit, t;
    std::getline(fields, index, ',');
    std::getline(fields, hit, ',');
    std::getline(fields, t, ',');
    REQUIRE(std::stoul(index) == out.size());
    out.push_back({hit == "1", t.empty() ? 0.0 : std::stod(t)});
  }
  return out;
}

}  // namespace

TEST_CASE("stored answers: every stored time-of-impact answer meets the acceptance rule against the oracle", "[stored]") {
  const auto queries = json_lines(datasets / "determinism" / "queries.jsonl");
  for (const char* mode : {"strict", "fixed"}) {
    const auto stored = answers(datasets / "determinism" / (std::string("answers_") + mode + ".csv"));
    REQUIRE(stored.size() == queries.size());
    int judged = 0, hits = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const ToiQuery q = parse_toi_query(queries[i]);
      const double rel_tol =
          std::string(mode) == "strict" ? 1e-12 : fixed_toi_gap_bound(q) / oracle_detail::scale_of(q);
      const Verdict v = judge_toi_answer(q, stored[i].hit, stored[i].t, rel_tol);
      INFO("answers_" << mode << ".csv, query " << i << " (tolerance " << rel_tol << " of the scale): " << v.why);
      CHECK(v.ok);
      ++judged;
      hits += stored[i].hit ? 1 : 0;
    }
    std::cout << "stored answers (" << mode << "): " << judged << " judged against the oracle, " << hits << " hits\n";
  }
}

// The hard set holds the oracle's answers (hit, t, min_gap, scale) beside
// each query. Checked by other means than the root isolation that found them:
//  - the scale is max(R, |Δv| H, ½ |Δa| H²), recomputed: the same bits;
//  - a hit's stored t is the oracle's root rounded to a double (≤ 2^-53 t):
//    the gap evaluated there in 60 digits is within the distance the pair
//    closes in that rounding, (|Δv| + |Δa| H) 2^-52 t, plus 1e-30 of the
//    scale (the oracle brackets its roots to 1e-42);
//  - the stored minimum gap (rounded to a double, 2^-53 of itself) is a
//    gap: at most the gap at 0 and at H; a hit has min_gap ≤ 0, a miss
//    min_gap > 0;
//  - a query of the families built to have their closest approach at gap
//    ±10^-k of the scale (at_relative_gap in src/lab/hard_queries.cpp:
//    grazing_ball_ball, grazing_wall_face, grazing_wall_end,
//    tiny_acceleration; gap_exponent k, gap_sign) has a minimum gap of that
//    sign and, for k ≤ 12 (above the doubles' rounding of the construction,
//    ~1e-16 of its coordinates, which are of the scale's size), of that
//    size to within 1 %. (The other graze families set the gap against a
//    radius or sit at 1e8: their construction rounds coarser than that.)
TEST_CASE("stored answers: the hard set's oracle answers agree with the gap and with how each query was built", "[stored]") {
  const auto lines = json_lines(datasets / "hard" / "hard_queries.jsonl");
  REQUIRE(lines.size() > 10000);
  int hits = 0, constructed = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const nlohmann::json& j = lines[i];
    const ToiQuery q = parse_toi_query(j);
    const nlohmann::json& o = j.at("oracle");
    const bool hit = o.at("hit").get<bool>();
    const double t = o.at("t").get<double>(), min_gap = o.at("min_gap").get<double>(), scale = o.at("scale").get<double>();
    INFO("hard_queries.jsonl line " << i + 1 << " (" << j.value("family", "?") << "): " << describe(q) << "; stored hit "
                                    << hit << " t " << t << " min_gap " << min_gap << " scale " << scale);
    CHECK(oracle_detail::scale_of(q) == scale);
    const Reference gap0 = oracle_gap_at(q, Reference(0)), gapH = oracle_gap_at(q, Reference(q.horizon));
    const Reference rounding(std::ldexp(std::fabs(min_gap), -52) + 1e-30 * scale);
    CHECK(Reference(min_gap) <= gap0 + rounding);
    CHECK(Reference(min_gap) <= gapH + rounding);
    if (hit) {
      ++hits;
      const bool ball = q.kind == QueryKind::ball_ball;
      const double dv = std::hypot(q.ball.velocity.x - (ball ? q.other.velocity.x : 0), q.ball.velocity.y - (ball ? q.other.velocity.y : 0));
      const double da = std::hypot(q.ball.acceleration.x - (ball ? q.other.acceleration.x : 0),
                                   q.ball.acceleration.y - (ball ? q.other.acceleration.y : 0));
      const double allowed = (dv + da * q.horizon) * std::ldexp(1.0, -52) * t + 1e-30 * scale;
      CHECK(t >= 0);
      CHECK(t <= q.horizon);
      CHECK(abs(oracle_gap_at(q, Reference(t))) <= Reference(allowed));
      CHECK(min_gap <= allowed);
    } else {
      CHECK(min_gap > 0);
    }
    const std::string family = j.value("family", "");
    const bool relative_gap = family == "grazing_ball_ball" || family == "grazing_wall_face" ||
                              family == "grazing_wall_end" || family == "tiny_acceleration";
    if (relative_gap && j.at("gap_sign").get<int>() != 0) {
      const int k = j.at("gap_exponent").get<int>(), sign = j.at("gap_sign").get<int>();
      const double built = sign * std::pow(10.0, -k) * scale;
      if (k <= 12) {
        ++constructed;
        CHECK(std::fabs(min_gap - built) <= 0.01 * std::fabs(built));
      }
    }
  }
  std::cout << "hard set: " << lines.size() << " oracle answers checked, " << hits << " hits, " << constructed
            << " closest approaches against their construction\n";
}

namespace {

// Every applicable physics check on the run `collide2d run SCENE --until T
// --mode M` makes, the run whose final hash is stored.
void run_behind_hash_obeys_the_checks(const std::string& scene_file, double until, const std::vector<std::string>& slugs,
                                      const std::vector<std::string>& modes) {
  const Scene scene = load_scene_file((datasets / "scenes" / scene_file).string());
  for (const std::string& mode : modes)
    for (const std::string& slug : slugs) {
      const NamedCheck* check = find_check(slug);
      REQUIRE(check != nullptr);
      INFO(scene_file << " for " << until << " s, " << mode << ": " << slug);
      CheckResult result;
      try {
        result = check->check(scene, mode, until);
      } catch (const NotApplicable& e) {
        FAIL("the check does not apply: " << e.what());
      }
      CHECK(result.value_or("holds") == "holds");
      std::cout << "stored hash run " << scene_file << " " << until << " s " << mode << ": " << slug << " "
                << result.value_or("holds") << "\n";
    }
}

}  // namespace

// datasets/determinism/abound_20s_{strict,fixed}.hash (cli.run_replay_abound_*).
// Abound's walls have restitution 0.9 and its balls 1: neither energy
// check applies (energy-kept wants every restitution 1, energy-never-rises
// every one below 1).
TEST_CASE("stored answers: the runs behind the Abound hashes obey the physics checks", "[stored]") {
  run_behind_hash_obeys_the_checks("abound.json", 20,
                                   {"no-overlap", "momentum-kept", "reflection-speed", "impulses-keep-momentum"},
                                   {"strict", "fixed"});
}

// datasets/determinism/dense_gas_400_50s_{strict,fixed}.hash: an elastic
// gas, so energy-kept applies. No overlap is checked in strict mode only
// (13 s of its own; the fixed run makes the same collisions to rounding).
// Hidden: ctest runs it as stored.dense_gas_hash_run, label slow.
TEST_CASE("stored answers: the runs behind the dense gas hashes obey the physics checks", "[.stored_slow]") {
  run_behind_hash_obeys_the_checks("dense_gas_400.json", 50,
                                   {"energy-kept", "momentum-kept", "reflection-speed", "impulses-keep-momentum"},
                                   {"strict", "fixed"});
  run_behind_hash_obeys_the_checks("dense_gas_400.json", 50, {"no-overlap"}, {"strict"});
}
