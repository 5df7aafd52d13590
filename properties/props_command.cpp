// collide2d props: the scene properties as a sweep (issue 16). Case c is a
// (property, mode) pair on a seed derived from --seed (props_results.hpp),
// run as the suite would run it (sweep_case.hpp); the outcomes go to one
// HDF5 file in case order. Under `mpirun -n K` the cases are shared among the
// ranks (cli/sharded_sweep.hpp) and rank 0 keeps the books:
//   OUT.parts.jsonl  every finished case, one flushed line each (the journal);
//   OUT.partial      the results so far, rewritten every few seconds and at
//                    once on a signal: readable after a kill, its /missing
//                    names the cases without an outcome;
//   OUT              written when every case is in; the other two go.
// `--resume` reads the journal and runs only the missing cases, on any K.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "cli/build_info.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/journal.hpp"
#include "cli/output_path.hpp"
#include "cli/progress.hpp"
#include "cli/ranks.hpp"
#include "cli/sharded_sweep.hpp"
#include "property_table.hpp"
#include "props_results.hpp"

namespace collide2d::cli {
namespace {

using properties::PropsCase;
using properties::PropsJournal;
using properties::PropsPlan;
using properties::PropsSession;
using properties::SceneProperty;

// "collide2" in ASCII: the suite's default seed (property_runner.hpp).
constexpr std::uint64_t default_sweep_seed = 0x636f6c6c69646532ULL;

struct PropsOptions {
  std::string output = "props.h5";
  std::int64_t cases = 100;
  std::uint64_t seed = default_sweep_seed;
  std::vector<std::string> properties;  // empty: every property but the open (pile) ones
  std::string mode = "all";
  int max_size = 100;
  int max_shrinks = 2000;
  std::string counterexamples;  // empty: OUTPUT.counterexamples
  bool resume = false, list = false;
  double snapshot_every = 2;
  std::string command_line;
};

std::string host_name() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return host;
}

// The (property, mode) pairs the options ask for, in table order. Throws
// std::runtime_error naming an unknown property or mode.
PropsPlan make_plan(const PropsOptions& o) {
  PropsPlan plan;
  plan.seeds = o.cases;
  plan.seed = o.seed;
  plan.max_size = o.max_size;
  plan.max_shrink_tries = o.max_shrinks;
  for (const std::string& name : o.properties)
    if (!properties::find_scene_property(name)) throw std::runtime_error("--properties: no property \"" + name + "\" (see --list)");
  if (o.mode != "all" && o.mode != "strict" && o.mode != "fixed" && o.mode != "both")
    throw std::runtime_error("--mode: \"" + o.mode + "\" is not all, strict, fixed or both");
  for (const SceneProperty& p : properties::scene_property_table()) {
    const bool named = std::find(o.properties.begin(), o.properties.end(), p.slug) != o.properties.end();
    if (o.properties.empty() ? p.open : !named) continue;
    for (const std::string& mode : p.modes)
      if (o.mode == "all" || o.mode == mode) plan.pairs.push_back({p.slug, mode});
  }
  if (plan.pairs.empty()) throw std::runtime_error("no property runs in mode " + o.mode);
  return plan;
}

void list_properties() {
  std::printf("%-30s %-13s %s\n", "property", "modes", "test case of collide2d_scene_properties");
  for (const SceneProperty& p : properties::scene_property_table()) {
    std::string modes;
    for (const std::string& m : p.modes) modes += (modes.empty() ? "" : ",") + m;
    std::printf("%-30s %-13s %s%s%s\n", p.slug.c_str(), modes.c_str(), p.test_case.c_str(),
                p.open ? " (open: not swept unless named)" : "", p.expect_counterexample ? " (expected to fail)" : "");
  }
}

// One case, on whichever rank: its journal line.
std::string run_case(const PropsPlan& plan, std::int64_t c, int rank, const std::string& host) {
  const auto& [slug, mode] = plan.pair(c);
  const auto start = std::chrono::steady_clock::now();
  PropsCase done;
  done.outcome = properties::run_sweep_case(*properties::find_scene_property(slug), mode, plan.case_seed(c),
                                            plan.case_size(c), plan.max_shrink_tries);
  done.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  done.rank = rank;
  done.host = host;
  return properties::case_line(c, done).dump();
}

// A failure's shrunk scene as a file of its own, with how to reproduce it.
std::string write_counterexample(const std::string& dir, const PropsPlan& plan, std::int64_t c, const PropsCase& done) {
  const auto& [slug, mode] = plan.pair(c);
  const SceneProperty& p = *properties::find_scene_property(slug);
  std::filesystem::create_directories(dir);
  const std::string stem = dir + "/" + slug + "-" + mode + "-case" + std::to_string(c);
  std::ofstream(stem + ".json") << done.outcome.counterexample << "\n";
  const nlohmann::json meta = {
      {"property", p.name},
      {"check", slug},
      {"mode", mode},
      {"case", c},
      {"seed", std::to_string(plan.case_seed(c))},
      {"size", plan.case_size(c)},
      {"failure", done.outcome.detail},
      {"reproduce", "RC_PARAMS=\"" + done.outcome.reproduce + "\" collide2d_scene_properties \"" + p.test_case + "\""},
      {"expected_failure", p.expect_counterexample}};
  std::ofstream(stem + ".meta.json") << meta.dump(2) << "\n";
  return stem + ".json";
}

// The summary per (property, mode): judged, failed, discarded.
int print_summary(const PropsPlan& plan, const PropsJournal& journal, const std::string& output) {
  int unexpected = 0;
  std::printf("%-30s %-7s %7s %7s %7s %7s\n", "property", "mode", "cases", "judged", "failed", "discard");
  for (std::size_t k = 0; k < plan.pairs.size(); ++k) {
    std::int64_t cases = 0, judged = 0, failed = 0, discarded = 0;
    for (std::int64_t c = static_cast<std::int64_t>(k) * plan.seeds; c < static_cast<std::int64_t>(k + 1) * plan.seeds; ++c) {
      ++cases;
      const auto it = journal.cases.find(c);
      if (it == journal.cases.end()) continue;
      const std::string& v = it->second.outcome.verdict;
      judged += v != "discard";
      failed += v == "fail";
      discarded += v == "discard";
    }
    const bool expected = properties::find_scene_property(plan.pairs[k].first)->expect_counterexample;
    if (failed > 0 && !expected) ++unexpected;
    std::printf("%-30s %-7s %7lld %7lld %7lld %7lld%s\n", plan.pairs[k].first.c_str(), plan.pairs[k].second.c_str(),
                static_cast<long long>(cases), static_cast<long long>(judged), static_cast<long long>(failed),
                static_cast<long long>(discarded), expected ? "  (failures expected)" : "");
  }
  std::printf("results: %s\n", output.c_str());
  return unexpected;
}

int run_props(const PropsOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const Ranks ranks = start_ranks();
  const std::string journal_path = o.output + ".parts.jsonl", partial = o.output + ".partial";
  const std::string counterexamples = o.counterexamples.empty() ? o.output + ".counterexamples" : o.counterexamples;
  const std::string host = host_name();
  PropsPlan plan;
  PropsJournal journal;
  std::optional<JournalWriter> writer;
  const RootDecision todo = agree_on_items(ranks, "props", [&] { plan = make_plan(o); }, [&] {
    for (const std::string& out : {o.output, journal_path, partial}) require_writable_output(out, {});
    if (o.resume) {
      journal = properties::read_props_journal(journal_path, plan);
    } else if (std::filesystem::exists(journal_path)) {
      throw std::runtime_error(journal_path + ": holds the finished cases of an interrupted sweep; --resume (with the "
                               "same options) runs the missing ones, or remove it to start afresh");
    }
    RootDecision run;
    for (std::int64_t c = 0; c < plan.total(); ++c)
      if (!journal.cases.count(c)) run.items.push_back(c);
    writer.emplace(journal_path, plan.to_json(), o.resume);
    const PropsSession session{ranks.size, static_cast<std::int64_t>(run.items.size()), utc_now(),
                               ranks.mpi ? mpi_library_description() : "none (one rank)"};
    writer->write(properties::session_line(session));
    journal.sessions.push_back(session);
    if (o.resume)
      std::cerr << "props: resuming from " << journal_path << ": " << journal.cases.size() << " of " << plan.total()
                << " cases finished, " << run.items.size() << " to run\n";
    return run;
  });
  if (todo.refusal != 0) return todo.refusal;

  // Rank 0's books (main thread only).
  std::optional<ProgressLine> progress;
  if (ranks.rank == 0) progress.emplace("props");
  // The partial file is rewritten whole, so its cost grows with the plan:
  // at most every snapshot_every seconds, and never more than a twentieth of
  // rank 0's time (the wait is at least 20 times the last write).
  bool dirty = false;
  auto last_snapshot = std::chrono::steady_clock::now();
  double snapshot_wait = o.snapshot_every;
  auto snapshot = [&] {
    const auto started = std::chrono::steady_clock::now();
    properties::write_props_file(partial + ".tmp", plan, journal, false, o.command_line);
    rename_into_place(partial + ".tmp", partial);
    dirty = false;
    last_snapshot = std::chrono::steady_clock::now();
    snapshot_wait = std::max(o.snapshot_every, 20 * std::chrono::duration<double>(last_snapshot - started).count());
  };
  ShardedSweep sweep;
  sweep.run = [&](std::int64_t c) { return run_case(plan, c, ranks.rank, host); };
  sweep.record = [&](std::int64_t, const std::string& line, int) {
    const nlohmann::json j = nlohmann::json::parse(line);
    writer->write(j);
    auto [c, done] = properties::case_of_line(j);
    if (done.outcome.verdict == "fail") {
      const std::string file = write_counterexample(counterexamples, plan, c, done);
      if (!properties::find_scene_property(plan.pair(c).first)->expect_counterexample) {
        progress->finish();
        std::cerr << "props: case " << c << " (" << plan.pair(c).first << ", " << plan.pair(c).second
                  << ") failed: " << done.outcome.detail.substr(0, done.outcome.detail.find('\n')) << "; shrunk scene "
                  << file << "\n";
      }
    }
    journal.cases[c] = std::move(done);
    dirty = true;
  };
  sweep.tick = [&] {
    const double finished = static_cast<double>(journal.cases.size());
    progress->update(finished, static_cast<double>(plan.total()),
                     std::to_string(journal.cases.size()) + " / " + std::to_string(plan.total()) + " cases on " +
                         std::to_string(ranks.size) + (ranks.size == 1 ? " rank" : " ranks"));
    if (dirty && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_snapshot).count() >= snapshot_wait)
      snapshot();
  };
  sweep.stopping = snapshot;
  const SweepStop stop = run_sharded_sweep(ranks, todo.items, sweep);
  if (ranks.rank != 0) return non_root_exit(ranks, stop);
  progress->finish();
  if (!stop.finished()) {
    snapshot();
    for (const std::string& e : stop.errors) std::cerr << "collide2d props: " << e << "\n";
    std::cerr << "collide2d props: " << (stop.signal ? "interrupted by " + signal_name(stop.signal) : std::string("stopped"))
              << " with " << journal.cases.size() << " of " << plan.total() << " cases finished; " << partial
              << " lists the missing ones (/missing); the same command with --resume runs only those\n";
    if (stop.signal) return interrupted_exit_code(stop.signal);
    stop_ranks(ranks);
    return exit_bad_input;
  }
  try {
    properties::write_props_file(partial, plan, journal, true, o.command_line);
    rename_into_place(partial, o.output);
  } catch (const std::exception& e) {
    std::cerr << "collide2d props: " << e.what() << " (the finished cases are kept in " << journal_path << ")\n";
    stop_ranks(ranks);
    return exit_bad_input;
  }
  std::filesystem::remove(journal_path);
  stop_ranks(ranks);
  const int unexpected = print_summary(plan, journal, o.output);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%lld cases in %.1f s on %d %s\n", static_cast<long long>(todo.items.size()), seconds, ranks.size,
              ranks.size == 1 ? "rank" : "ranks");
  return unexpected > 0 ? exit_verification_failed : exit_ok;
}

}  // namespace

Runner add_props_command(CLI::App& app) {
  auto o = std::make_shared<PropsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "props", "The scene properties as a sweep: case i = property x mode x the i-th seed from --seed; outcomes to HDF5");
  cmd->add_option("-o,--output", o->output, "HDF5 file for the outcomes")->capture_default_str();
  cmd->add_option("--cases", o->cases, "seeds per (property, mode) pair")->capture_default_str()->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--seed", o->seed, "the sweep's seed (default: the suite's, \"collide2\" in ASCII)")->capture_default_str();
  cmd->add_option("--properties", o->properties, "properties to sweep (default: all but the open pile ones; see --list)")
      ->delimiter(',');
  cmd->add_option("--mode", o->mode, "strict, fixed, both (fixed against strict) or all")->capture_default_str();
  cmd->add_option("--max-size", o->max_size, "RapidCheck's size: case sizes cycle 0..N")->capture_default_str()->check(CLI::Range(0, 10000));
  cmd->add_option("--max-shrinks", o->max_shrinks, "shrink candidates tried per failure")->capture_default_str()->check(CLI::Range(0, 1000000));
  cmd->add_option("--counterexamples", o->counterexamples, "folder for shrunk failing scenes (default: OUTPUT.counterexamples)");
  cmd->add_flag("--resume", o->resume, "run only the cases missing from OUTPUT.parts.jsonl (same options, any number of ranks)");
  cmd->add_flag("--list", o->list, "list the properties and exit");
  cmd->footer("Under mpirun -n K, rank r runs cases r, r + K, ... of those to run and rank 0 writes the one file;\n"
              "the outcomes do not depend on K (timings and ranks are under /timing and /provenance).\n"
              "A failure names the suite's command that reproduces it on one machine (RC_PARAMS=\"reproduce=...\").\n"
              "Layout: docs/formats/props-file.md. Exit 0: no unexpected failure; 1: one or more; 2: bad input.");
  return [o, cmd] {
    if (o->list) {
      list_properties();
      return exit_ok;
    }
    o->command_line = command_line_of(*cmd);
    return run_props(*o);
  };
}

}  // namespace collide2d::cli
