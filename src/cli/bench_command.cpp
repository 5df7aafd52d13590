// collide2d bench: the benchmarks, each printing CSV.
//   toi: throughput of every time-of-impact method and mode on generated
//        query families and on the engine's own query mixes (engine_gas,
//        engine_abound: lab/engine_queries.hpp):
//        family,method,mode,queries,ns_per_query,hits.
//   sim: whole runs of hard-disk gases and settling scenes (bench_sim.hpp).
//   lcp: the island complementarity problems of lattice piles (bench_lcp.hpp).
//   peers: collide2d, Box2D and Chipmunk on the same scenes (bench_peers.hpp;
//        built when both are installed).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>
#include <vector>

#include "cli/bench_lcp.hpp"
#include "cli/bench_peers.hpp"
#include "cli/bench_sim.hpp"
#include "cli/commands.hpp"
#include "cli/parse_options.hpp"
#include "lab/engine_queries.hpp"
#include "lab/random_queries.hpp"

namespace collide2d::cli {
namespace {

struct BenchOptions {
  std::string what;
  std::size_t queries = 1000000;
  std::uint64_t seed = 2026;
  std::vector<std::string> methods{"analytic", "bisection", "seed"};
  std::vector<std::string> modes = number_mode_names();
  std::vector<std::string> families;  // empty: all
  double eps = 1e-9;
  BenchSimOptions sim;
  BenchPeersOptions peers;
  BenchLcpOptions lcp;
};

struct Timing {
  double ns_per_query;
  std::size_t hits;
};

// One pass over the queries, already converted to Num so that only the
// time-of-impact work is timed. The sum of times keeps the optimiser honest.
template <class Num>
Timing time_queries(const std::vector<ToiQueryOf<Num>>& queries, ToiMethod method, const Num& eps) {
  std::size_t hits = 0;
  Num time_sum{};
  const auto start = std::chrono::steady_clock::now();
  for (const auto& q : queries) {
    const ToiResult<Num> r = solve_toi_query(q, method, eps);
    // Counted without a branch: the harness should not add a mispredicted
    // jump of its own to every query.
    hits += r.hit() ? 1 : 0;
    time_sum = time_sum + (r.hit() ? r.time : Num{});
  }
  const auto stop = std::chrono::steady_clock::now();
  volatile double sink = NumberTraits<Num>::to_double(time_sum);
  (void)sink;
  const double ns = std::chrono::duration<double, std::nano>(stop - start).count();
  return {ns / static_cast<double>(queries.size()), hits};
}

// `family`: a generated family or an engine mix (bench toi's family column).
template <class Num>
void bench_mode(const std::string& family, const std::vector<ToiQuery>& queries, const BenchOptions& o) {
  std::vector<ToiQueryOf<Num>> converted;
  converted.reserve(queries.size());
  for (const auto& q : queries) converted.push_back(convert_query<Num>(q));
  const bool only_balls = std::all_of(queries.begin(), queries.end(), [](const ToiQuery& q) { return q.kind == QueryKind::ball_ball; });
  for (const std::string& method_name : o.methods) {
    const ToiMethod method = method_names.at(method_name);
    // The article's ball method is bisection: `seed` on ball pairs alone would
    // time bisection again under another name.
    if (only_balls && method == ToiMethod::seed) continue;
    const Timing t = time_queries(converted, method, num<Num>(o.eps));
    std::printf("%s,%s,%s,%zu,%.1f,%zu\n", family.c_str(), method_name.c_str(), NumberTraits<Num>::name, queries.size(),
                t.ns_per_query, t.hits);
    std::fflush(stdout);
  }
}

bool wanted(const BenchOptions& o, const std::string& family) {
  return o.families.empty() || std::find(o.families.begin(), o.families.end(), family) != o.families.end();
}

void bench_all_modes(const std::string& family, const std::vector<ToiQuery>& queries, const BenchOptions& o) {
  for (const std::string& mode : o.modes)
    with_number_type(number_mode_of(mode), [&](auto type) { bench_mode<typename decltype(type)::type>(family, queries, o); });
}

int run_bench(BenchOptions o) {
  if (o.what == "sim") {
    o.sim.modes = o.modes;
    return run_bench_sim(o.sim);
  }
  if (o.what == "lcp") {
    o.lcp.modes = o.modes;
    o.lcp.seed = o.seed;
    return run_bench_lcp(o.lcp);
  }
  if (o.what == "peers") {
#ifdef COLLIDE2D_HAVE_PEERS
    return run_bench_peers(o.peers);
#else
    std::cerr << "collide2d bench peers: this build has no peers (install libbox2d-dev and chipmunk-dev, configure again)\n";
    return exit_bad_input;
#endif
  }
  if (o.what != "toi") {
    std::cerr << "collide2d bench: unknown benchmark '" << o.what << "' (available: toi, sim, lcp, peers)\n";
    return exit_bad_input;
  }
  std::printf("family,method,mode,queries,ns_per_query,hits\n");
  for (QueryFamily family : all_query_families()) {
    if (!wanted(o, to_string(family))) continue;
    std::cerr << "bench: generating " << o.queries << " " << to_string(family) << " queries\n";
    SplitMix64 rng(o.seed + static_cast<std::uint64_t>(family));
    std::vector<ToiQuery> queries;
    queries.reserve(o.queries);
    for (std::size_t i = 0; i < o.queries; ++i) queries.push_back(random_query(family, rng));
    bench_all_modes(to_string(family), queries, o);
  }
  // The engine's own mixes: the queries a run asks, in the order it asks them.
  for (const std::string& mix : engine_query_mixes()) {
    if (!wanted(o, mix)) continue;
    std::cerr << "bench: gathering " << o.queries << " queries from the engine (" << mix << ")\n";
    bench_all_modes(mix, engine_queries(engine_mix_scene(mix), o.queries), o);
  }
  return exit_ok;
}

}  // namespace

Runner add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "throughput benchmarks (single thread); prints CSV");
  cmd->add_option("WHAT", o->what, "which benchmark: toi (time-of-impact queries), sim (whole runs), lcp (island contact problems), peers (against Box2D and Chipmunk)")->required();
  cmd->add_option("--queries", o->queries, "queries generated per family")->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the query generator (lcp: of the masses and active sets)")->capture_default_str();
  cmd->add_option("--methods", o->methods, "methods to time")
      ->check(CLI::IsMember({"analytic", "bisection", "seed"}))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--modes", o->modes, "number modes to time")
      ->check(CLI::IsMember(number_mode_names()))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--families", o->families, "query families (default: all)")
      ->check(CLI::IsMember({"ball_wall", "ball_wall_gravity", "ball_ball_quadratic", "ball_ball_quartic", "engine_gas", "engine_abound"}))
      ->delimiter(',');
  cmd->add_option("--eps", o->eps, "tolerance of the bisection method")->check(finite_positive())->capture_default_str();
  cmd->add_option("--sizes", o->sim.sizes, "sim: numbers of discs of the gases")->check(CLI::Range(std::int64_t{1}, std::int64_t{100000000}))->delimiter(',')->capture_default_str();
  cmd->add_option("--etas", o->sim.etas, "sim: packing fractions of the gases")
      ->check(finite_number_in(0.0, false, 0.7, "a packing fraction in (0, 0.7), where the gas generator can place the discs"))
      ->delimiter(',')->capture_default_str();
  cmd->add_flag("--large", o->sim.large, "sim: also gases of 10^5 and 10^6 discs");
  cmd->add_option("--collisions", o->sim.collisions, "sim: collisions a gas run is sized for (Enskog's rate)")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--speed", o->sim.speed, "sim: speed of every disc at the start")->check(finite_positive())->capture_default_str();
  cmd->add_flag("!--no-settling", o->sim.settling, "sim: leave out the Abound and settling-pile rows");
  cmd->add_option("--gas-seconds", o->peers.gas_seconds, "peers: simulated seconds of each dense gas")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--pile-seconds", o->peers.pile_seconds, "peers: simulated seconds of the settling pile")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--widths", o->lcp.widths, "lcp: balls a row of each lattice pile")
      ->check(CLI::Range(std::int64_t{2}, std::int64_t{60}))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--keep", o->sim.keep, "sim: keep the scenes, run files and summaries in this folder");
  return [o] { return run_bench(*o); };
}

}  // namespace collide2d::cli
