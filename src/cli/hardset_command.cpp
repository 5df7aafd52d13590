// collide2d hardset: the hard time-of-impact dataset (datasets/hard/), every
// query with the high-precision oracle's answer, as JSON Lines (readable by
// `collide2d toi` and `collide2d study`) and as HDF5 (for analysis).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/datasets.hpp"
#include "cli/interrupt.hpp"
#include "cli/output_path.hpp"
#include "cli/progress.hpp"
#include "lab/hard_queries.hpp"
#include "lab/oracle.hpp"
#include "lab/table_file.hpp"

namespace collide2d::cli {
namespace {

struct HardsetOptions {
  std::string h5 = dataset_path("hard/hard_queries.h5");
  std::string jsonl = dataset_path("hard/hard_queries.jsonl");
  std::uint64_t seed = 2026;
  int per_family = 1000;
};

nlohmann::json ball_json(const BallState<double>& b) {
  return {{"position", {b.position.x, b.position.y}},
          {"velocity", {b.velocity.x, b.velocity.y}},
          {"acceleration", {b.acceleration.x, b.acceleration.y}},
          {"radius", b.radius}};
}

// The query as a `collide2d toi` line, plus its family and the oracle's answer.
nlohmann::json query_line(const HardQuery& h, const OracleAnswer& o) {
  const ToiQuery& q = h.query;
  nlohmann::json line = {{"horizon", q.horizon}, {"family", h.family}, {"gap_exponent", h.gap_exponent}, {"gap_sign", h.gap_sign}};
  line["balls"] = nlohmann::json::array({ball_json(q.ball)});
  if (q.kind == QueryKind::ball_ball) line["balls"].push_back(ball_json(q.other));
  else line["walls"] = nlohmann::json::array({{{"a", {q.wall.a.x, q.wall.a.y}}, {"b", {q.wall.b.x, q.wall.b.y}}}});
  line["oracle"] = {{"hit", o.hit}, {"t", o.t}, {"min_gap", o.min_gap}, {"scale", o.scale}};
  return line;
}

void write_h5(const std::string& path, const HardsetOptions& opt, const std::vector<HardQuery>& set,
              const std::vector<OracleAnswer>& answers) {
  TableFile f(path);
  f.attribute("/", "format", std::string("collide2d hard queries 1"));
  f.attribute("/", "seed", static_cast<std::int64_t>(opt.seed));
  f.attribute("/", "per_family", static_cast<std::int64_t>(opt.per_family));
  f.attribute("/", "regenerate", "collide2d hardset --seed " + std::to_string(opt.seed) + " --per-family " +
                                     std::to_string(opt.per_family));
  std::vector<std::string> family;
  std::vector<std::int64_t> kind, k, sign, hit;
  std::vector<double> ball, other, wall, horizon, t, min_gap, scale;
  auto put = [](std::vector<double>& v, const BallState<double>& b) {
    v.insert(v.end(), {b.position.x, b.position.y, b.velocity.x, b.velocity.y, b.acceleration.x, b.acceleration.y, b.radius});
  };
  for (std::size_t i = 0; i < set.size(); ++i) {
    const ToiQuery& q = set[i].query;
    family.push_back(set[i].family);
    kind.push_back(q.kind == QueryKind::ball_ball ? 1 : 0);
    k.push_back(set[i].gap_exponent);
    sign.push_back(set[i].gap_sign);
    put(ball, q.ball);
    put(other, q.other);
    wall.insert(wall.end(), {q.wall.a.x, q.wall.a.y, q.wall.b.x, q.wall.b.y});
    horizon.push_back(q.horizon);
    hit.push_back(answers[i].hit ? 1 : 0);
    t.push_back(answers[i].t);
    min_gap.push_back(answers[i].min_gap);
    scale.push_back(answers[i].scale);
  }
  const std::uint64_t n = set.size();
  f.write("/queries/family", family);
  f.write("/queries/kind", kind);
  f.write("/queries/gap_exponent", k);
  f.write("/queries/gap_sign", sign);
  f.write("/queries/ball", ball, {n, 7});
  f.write("/queries/other", other, {n, 7});
  f.write("/queries/wall", wall, {n, 4});
  f.write("/queries/horizon", horizon);
  f.attribute("/queries", "kind", std::string("0: ball-wall (ball, wall), 1: ball-ball (ball, other)"));
  f.attribute("/queries", "ball_columns", std::string("px py vx vy ax ay r"));
  f.attribute("/queries", "wall_columns", std::string("ax ay bx by"));
  f.write("/oracle/hit", hit);
  f.write("/oracle/t", t);
  f.write("/oracle/min_gap", min_gap);
  f.write("/oracle/scale", scale);
  f.attribute("/oracle", "about", std::string("Boost.Multiprecision (lab/oracle.hpp): first contact t, min over [0, H] "
                                              "of distance minus contact distance, scale = max(R, |dv| H, |da| H^2 / 2)"));
}

// Both outputs are written under OUT.partial and renamed into place only
// when both are complete: a failed or interrupted run leaves the old files.
int run_hardset(const HardsetOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  if (opt.h5 == opt.jsonl) {
    std::cerr << opt.h5 << ": named for both outputs (--jsonl and -o)\n";
    return exit_bad_input;
  }
  for (const std::string& out : {opt.jsonl, opt.h5})
    if (const std::string problem = output_path_problem(out, {}); !problem.empty()) {
      std::cerr << problem << "\n";
      return exit_bad_input;
    }
  install_interrupt_handlers();
  const std::vector<HardQuery> drawn = hard_query_set(opt.seed, opt.per_family);
  std::vector<HardQuery> set;
  std::vector<OracleAnswer> answers;
  std::map<std::string, int> per_family, dropped;
  try {
    ProgressLine progress("hardset, oracle");
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      // A query must start apart (the toi reader refuses overlaps at t = 0).
      if (oracle_gap_at(drawn[i].query, Reference(0)) < 0) {
        ++dropped[drawn[i].family];
        continue;
      }
      set.push_back(drawn[i]);
      answers.push_back(oracle_time_of_impact(drawn[i].query));
      ++per_family[drawn[i].family];
      progress.update(static_cast<double>(i + 1), static_cast<double>(drawn.size()),
                      std::to_string(i + 1) + " / " + std::to_string(drawn.size()) + " queries");
      throw_if_interrupted();
    }
  } catch (const Interrupted& e) {
    std::cerr << "collide2d hardset: " << e.what() << "; nothing written (" << opt.jsonl << " and " << opt.h5
              << " are as they were)\n";
    return interrupted_exit_code(e.signal);
  }
  const std::string jsonl_partial = opt.jsonl + ".partial", h5_partial = opt.h5 + ".partial";
  try {
    std::ofstream out(jsonl_partial);
    if (!out) throw std::runtime_error(jsonl_partial + ": cannot write the file");
    for (std::size_t i = 0; i < set.size(); ++i) out << query_line(set[i], answers[i]).dump() << "\n";
    out.close();
    if (!out) throw std::runtime_error(jsonl_partial + ": error writing the file");
    write_h5(h5_partial, opt, set, answers);
    rename_into_place(jsonl_partial, opt.jsonl);
    rename_into_place(h5_partial, opt.h5);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(jsonl_partial, ec);
    std::filesystem::remove(h5_partial, ec);
    std::cerr << "collide2d hardset: " << e.what() << "\n";
    return exit_bad_input;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%-26s %8s %8s %8s\n", "family", "queries", "hits", "dropped");
  for (const std::string& name : hard_query_families()) {
    int hits = 0;
    for (std::size_t i = 0; i < set.size(); ++i) hits += set[i].family == name && answers[i].hit ? 1 : 0;
    std::printf("%-26s %8d %8d %8d\n", name.c_str(), per_family[name], hits, dropped[name]);
  }
  std::printf("%zu queries -> %s, %s (%.1f s)\n", set.size(), opt.jsonl.c_str(), opt.h5.c_str(), seconds);
  return exit_ok;
}

}  // namespace

Runner add_hardset_command(CLI::App& app) {
  auto opt = std::make_shared<HardsetOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hardset", "Generate the hard time-of-impact dataset (datasets/hard/) with the high-precision oracle's answers");
  cmd->add_option("--seed", opt->seed, "random seed (the shipped set uses the default)")->capture_default_str();
  cmd->add_option("--per-family", opt->per_family, "about this many queries per family")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--jsonl", opt->jsonl, "JSON Lines output, one query per line (collide2d toi reads it)")->capture_default_str();
  cmd->add_option("-o,--output", opt->h5, "HDF5 output")->capture_default_str();
  return [opt] { return run_hardset(*opt); };
}

}  // namespace collide2d::cli
