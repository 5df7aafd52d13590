// collide2d study: what each time-of-impact method costs and how wrong it
// gets, at the query level (every method and mode over a dataset with the
// oracle's answers) and at the scene level (the step engine over a sweep of
// dt and the event engine, against a reference run). Results go to one HDF5
// file (layout in docs/STUDY.md; analysis/plot_study.py draws it) and a
// table is printed.
#include <sys/utsname.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ctime>
#include <optional>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli/build_info.hpp"
#include "cli/commands.hpp"
#include "cli/datasets.hpp"
#include "cli/interrupt.hpp"
#include "cli/journal.hpp"
#include "cli/option_checks.hpp"
#include "cli/output_path.hpp"
#include "cli/progress.hpp"
#include "cli/ranks.hpp"
#include "cli/sharded_sweep.hpp"
#include "cli/study_parts.hpp"
#include "collide2d/scene/builtin_scene.hpp"
#include "lab/query_study.hpp"
#include "lab/scene_study.hpp"
#include "lab/table_file.hpp"

#ifndef COLLIDE2D_BUILD_TYPE
#define COLLIDE2D_BUILD_TYPE "unknown"
#endif

namespace collide2d::cli {
namespace {

struct StudyOptions {
  std::string output = "study.h5";
  std::string queries = dataset_path("hard/hard_queries.jsonl");
  int limit_per_family = 0;
  int repeats = 10;
  std::vector<std::string> scenes{dataset_path("scenes/gas.json"), "abound"};
  double until = 0;  // 0: each scene's own duration
  std::vector<double> dts{1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
  bool no_queries = false, no_scenes = false;
  bool resume = false;
  std::string command_line;
  // What decides the results: a parts file is resumed only with these.
  nlohmann::json results_options() const {
    return {{"queries", queries}, {"limit_per_family", limit_per_family}, {"repeats", repeats}, {"scenes", scenes},
            {"until", until},     {"dts", dts},                           {"no_queries", no_queries}, {"no_scenes", no_scenes}};
  }
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}


// A scene by path, or "abound" for the built-in one; named by its file stem.
std::pair<std::string, Scene> load_named_scene(const std::string& spec) {
  if (spec == "abound") return {"abound", parse_scene(nlohmann::json::parse(builtin_abound_scene_json()))};
  std::string name = spec.substr(spec.find_last_of('/') + 1);
  name = name.substr(0, name.rfind('.'));
  try {
    return {name, load_scene_file(spec)};
  } catch (const SceneError& e) {
    throw std::runtime_error(spec + ": " + e.what());
  }
}

void print_query_table(const std::vector<QueryStudyRow>& rows, bool all_only) {
  std::printf("%-24s %-20s %-6s %6s %5s %5s %5s %6s %9s %9s %9s %9s\n", "family", "method", "mode", "n", "FN", "FP", "late",
              ">bound", "ns med", "ns p99", "err p99", "err max");
  for (const QueryStudyRow& r : rows) {
    if (all_only != (r.family == "all")) continue;
    std::printf("%-24s %-20s %-6s %6lld %5lld %5lld %5lld %6lld %9.0f %9.0f %9.2e %9.2e\n", r.family.c_str(),
                r.method.c_str(), r.mode.c_str(), static_cast<long long>(r.queries), static_cast<long long>(r.false_negatives),
                static_cast<long long>(r.false_positives), static_cast<long long>(r.late_reports),
                static_cast<long long>(r.over_bound), r.ns_median, r.ns_p99, r.error_p99, r.error_max);
  }
}

void print_scene_table(const std::vector<SceneStudyRun>& runs) {
  std::printf("%-8s %-6s %-15s %-6s %7s %9s %10s %9s %9s %8s %9s %7s\n", "scene", "engine", "method", "mode", "dt",
              "wall s", "events", "energy", "diverge", "lambda", "faithful", "missed");
  for (const SceneStudyRun& r : runs)
    std::printf("%-8s %-6s %-15s %-6s %7.0e %9.3f %10lld %9.2e %9.2e %8.3g %9.3g %7lld\n", r.scene.c_str(),
                r.engine.c_str(), r.method.c_str(), r.mode.c_str(), r.dt, r.wall_seconds, static_cast<long long>(r.events),
                r.energy_error_max, r.divergence_final, r.growth_rate, r.faithful_until,
                static_cast<long long>(r.missed_contacts));
  for (const SceneStudyRun& r : runs)
    if (!r.failure.empty())
      std::printf("  %s %s %s %s dt %g stopped early: %s\n", r.scene.c_str(), r.engine.c_str(), r.method.c_str(),
                  r.mode.c_str(), r.dt, r.failure.c_str());
}

template <class Row, class Get>
auto column(const std::vector<Row>& rows, Get get) {
  std::vector<decltype(get(rows.front()))> out;
  for (const Row& r : rows) out.push_back(get(r));
  return out;
}

void write_query_level(TableFile& f, const StudyOptions& o, const std::vector<QueryStudyRow>& rows) {
  f.attribute("/query", "dataset", o.queries);
  f.attribute("/query", "repeats", static_cast<std::int64_t>(o.repeats));
  f.attribute("/query", "tolerance", std::string("false negative / positive judged at 1e-12 of each query's scale"));
  const std::string t = "/query/table/";
  f.write(t + "family", column(rows, [](const QueryStudyRow& r) { return r.family; }));
  f.write(t + "method", column(rows, [](const QueryStudyRow& r) { return r.method; }));
  f.write(t + "mode", column(rows, [](const QueryStudyRow& r) { return r.mode; }));
  f.write(t + "queries", column(rows, [](const QueryStudyRow& r) { return r.queries; }));
  f.write(t + "oracle_hits", column(rows, [](const QueryStudyRow& r) { return r.oracle_hits; }));
  f.write(t + "false_negatives", column(rows, [](const QueryStudyRow& r) { return r.false_negatives; }));
  f.write(t + "false_positives", column(rows, [](const QueryStudyRow& r) { return r.false_positives; }));
  f.write(t + "late_reports", column(rows, [](const QueryStudyRow& r) { return r.late_reports; }));
  f.write(t + "rule_failures", column(rows, [](const QueryStudyRow& r) { return r.over_bound; }));
  f.write(t + "threw", column(rows, [](const QueryStudyRow& r) { return r.threw; }));
  f.write(t + "ns_median", column(rows, [](const QueryStudyRow& r) { return r.ns_median; }));
  f.write(t + "ns_p99", column(rows, [](const QueryStudyRow& r) { return r.ns_p99; }));
  f.write(t + "ns_max", column(rows, [](const QueryStudyRow& r) { return r.ns_max; }));
  f.write(t + "error_median", column(rows, [](const QueryStudyRow& r) { return r.error_median; }));
  f.write(t + "error_p99", column(rows, [](const QueryStudyRow& r) { return r.error_p99; }));
  f.write(t + "error_max", column(rows, [](const QueryStudyRow& r) { return r.error_max; }));
  f.write(t + "time_error_median", column(rows, [](const QueryStudyRow& r) { return r.time_error_median; }));
  f.write(t + "time_error_p99", column(rows, [](const QueryStudyRow& r) { return r.time_error_p99; }));
  f.write(t + "time_error_max", column(rows, [](const QueryStudyRow& r) { return r.time_error_max; }));
}

// Query by query: /query/per_query/family (the dataset's order), and per
// method and mode a group NN with attributes method, mode.
void write_per_query(TableFile& f, const std::vector<std::string>& families, const std::vector<PerQueryResults>& per) {
  f.write("/query/per_query/family", families);
  for (std::size_t i = 0; i < per.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/query/per_query/%02zu", i);
    const std::string g = name;
    f.write(g + "/ns", per[i].ns);
    f.write(g + "/error", per[i].error);
    f.write(g + "/time_error", per[i].time_error);
    f.write(g + "/hit", per[i].hit);
    f.attribute(g, "method", per[i].method);
    f.attribute(g, "mode", per[i].mode);
  }
}

void write_scene_level(TableFile& f, const StudyOptions& o, const std::vector<SceneStudyRun>& runs) {
  f.attribute("/scene", "reference", std::string("the event engine in 60-digit arithmetic (Boost.Multiprecision), same scene"));
  f.attribute("/scene", "until", o.until);
  std::string scenes, dts;
  for (const std::string& sc : o.scenes) scenes += (scenes.empty() ? "" : " ") + sc;
  for (const double dt : o.dts) dts += (dts.empty() ? "" : " ") + std::to_string(dt);
  f.attribute("/scene", "scenes", scenes);
  f.attribute("/scene", "dts", dts);
  const std::string t = "/scene/table/";
  f.write(t + "scene", column(runs, [](const SceneStudyRun& r) { return r.scene; }));
  f.write(t + "engine", column(runs, [](const SceneStudyRun& r) { return r.engine; }));
  f.write(t + "method", column(runs, [](const SceneStudyRun& r) { return r.method; }));
  f.write(t + "mode", column(runs, [](const SceneStudyRun& r) { return r.mode; }));
  f.write(t + "dt", column(runs, [](const SceneStudyRun& r) { return r.dt; }));
  f.write(t + "wall_seconds", column(runs, [](const SceneStudyRun& r) { return r.wall_seconds; }));
  f.write(t + "energy_error_max", column(runs, [](const SceneStudyRun& r) { return r.energy_error_max; }));
  f.write(t + "divergence_final", column(runs, [](const SceneStudyRun& r) { return r.divergence_final; }));
  f.write(t + "growth_rate", column(runs, [](const SceneStudyRun& r) { return r.growth_rate; }));
  f.write(t + "fit_from", column(runs, [](const SceneStudyRun& r) { return r.fit_from; }));
  f.write(t + "fit_to", column(runs, [](const SceneStudyRun& r) { return r.fit_to; }));
  f.write(t + "faithful_until", column(runs, [](const SceneStudyRun& r) { return r.faithful_until; }));
  f.write(t + "failure", column(runs, [](const SceneStudyRun& r) { return r.failure; }));
  f.write(t + "events", column(runs, [](const SceneStudyRun& r) { return r.events; }));
  f.write(t + "missed_contacts", column(runs, [](const SceneStudyRun& r) { return r.missed_contacts; }));
  f.write(t + "frames", column(runs, [](const SceneStudyRun& r) { return r.frames; }));
  f.write(t + "deepest_overlap", column(runs, [](const SceneStudyRun& r) { return r.deepest_overlap; }));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/scene/divergence/%03zu/", i);
    f.write(std::string(name) + "time", runs[i].time);
    f.write(std::string(name) + "divergence", runs[i].divergence);
  }
}

// The study's results into `path`: attributes, then each level present.
void write_study_file(const std::string& path, const StudyOptions& o, const Ranks& ranks, const QueryStudy& query_study,
                      const std::vector<std::string>& query_families, const std::vector<SceneStudyRun>& scene_runs) {
  TableFile f(path);
  write_sweep_provenance(f, ranks);
  f.attribute("/", "format", std::string("collide2d study 1"));
  f.attribute("/", "created", utc_now());
  f.attribute("/", "command", o.command_line);
  f.attribute("/", "compiler", compiler_description());
  f.attribute("/", "build_type", std::string(COLLIDE2D_BUILD_TYPE));
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  f.attribute("/", "hostname", std::string(host));
  f.attribute("/", "cpu", cpu_model());
  f.attribute("/", "cores", static_cast<std::int64_t>(std::thread::hardware_concurrency()));
  if (!query_study.rows.empty()) {
    write_query_level(f, o, query_study.rows);
    write_per_query(f, query_families, query_study.per_query);
  }
  if (!scene_runs.empty()) write_scene_level(f, o, scene_runs);
}

void print_study_tables(const StudyOptions& o, const QueryStudy& query_study, const std::vector<SceneStudyRun>& scene_runs) {
  if (!query_study.rows.empty()) {
    std::printf("Query level (%s): per method and mode over all families. FN/FP: false negatives/positives at\n"
                "1e-12 of each query's scale; late: a contact reported after the first one was passed through; >bound:\n"
                "outside the method's stated bound; ns: per query; err: |true gap\n"
                "at the reported time| / scale (a missed contact: its depth / scale)\n", o.queries.c_str());
    print_query_table(query_study.rows, true);
    std::printf("\nPer family:\n");
    print_query_table(query_study.rows, false);
  }
  if (!scene_runs.empty()) {
    std::printf("\nScene level (reference: the event engine in 60-digit arithmetic; energy = max |E - E_ref| / |E_ref(0)|; diverge = RMS\n"
                "position difference at the end; lambda = fitted growth rate 1/s; faithful = first time the divergence\n"
                "exceeds 1e-3 of the smallest radius; missed = centres that went through a wall):\n");
    print_scene_table(scene_runs);
  }
}

// The study's parts: the query units (one method in one mode each, in the
// order of query_study_units) and then the scenes. Under `mpirun -n K` they
// are shared among the ranks (cli/sharded_sweep.hpp); rank 0 keeps every
// finished part in the parts file at once (study_parts.hpp) and, when all
// are in, writes the HDF5 file under OUT.partial and renames it into place,
// so OUT is either complete or absent. The results are the parts in their
// order, whatever K was: only the times (ns_*, wall_seconds) and
// /provenance depend on it.
struct StudyInputs {
  std::vector<StudyQuery> queries;
  std::vector<std::string> query_families;
  std::vector<QueryStudyUnit> units;
  std::vector<std::pair<std::string, Scene>> scenes;
  std::size_t parts() const { return units.size() + scenes.size(); }
};

StudyInputs load_study_inputs(const StudyOptions& o) {
  StudyInputs in;
  if (!o.no_queries) {
    in.queries = read_study_queries(o.queries, o.limit_per_family);
    for (const StudyQuery& q : in.queries) in.query_families.push_back(q.family);
    in.units = query_study_units();
  }
  if (!o.no_scenes)
    for (const std::string& spec : o.scenes) in.scenes.push_back(load_named_scene(spec));
  return in;
}

// Part `item` of the study, as its parts-file line.
std::string run_study_part(const StudyOptions& o, const StudyInputs& in, std::int64_t item) {
  const std::size_t k = static_cast<std::size_t>(item);
  if (k < in.units.size()) {
    const QueryStudyUnitResult unit =
        run_query_study_unit(in.queries, in.units[k], o.repeats, [](std::size_t) { throw_if_interrupted(); });
    return query_unit_part(k, unit).dump();
  }
  const auto& [name, scene] = in.scenes.at(k - in.units.size());
  const double until = o.until > 0 ? std::min(o.until, scene.duration) : scene.duration;
  const std::vector<SceneStudyRun> runs =
      run_scene_study(name, scene, until, o.dts, [](const std::string&) { throw_if_interrupted(); });
  return scene_part(name, runs).dump();
}

// Rank 0: checks the outputs and reads what an interrupted study finished;
// returns the parts still to run, or a refusal (said on stderr).
RootDecision plan_study(const StudyOptions& o, const StudyInputs& in, StudyParts& done) {
  std::vector<std::string> inputs;
  if (!o.no_queries) inputs.push_back(o.queries);
  if (!o.no_scenes)
    for (const std::string& spec : o.scenes)
      if (spec != "abound") inputs.push_back(spec);
  const std::string parts_path = study_parts_path(o.output);
  for (const std::string& out : {o.output, parts_path, o.output + ".partial"})
    if (const std::string problem = output_path_problem(out, inputs); !problem.empty()) {
      std::cerr << problem << "\n";
      return {exit_bad_input, {}};
    }
  if (o.resume) {
    done = read_study_parts(parts_path, o.results_options());
    std::cerr << "study: resuming from " << parts_path << " (" << done.query_units.size() << " query units and "
              << done.scenes.size() << " scenes finished)\n";
  } else if (std::filesystem::exists(parts_path)) {
    std::cerr << parts_path << ": holds the finished parts of an interrupted study; --resume (with the same options) "
              << "continues it, or remove it to start afresh\n";
    return {exit_bad_input, {}};
  }
  RootDecision todo;
  for (std::size_t k = 0; k < in.parts(); ++k) {
    const bool finished = k < in.units.size() ? done.query_units.count(k) > 0
                                              : done.scenes.count(in.scenes[k - in.units.size()].first) > 0;
    if (!finished) todo.items.push_back(static_cast<std::int64_t>(k));
  }
  return todo;
}

int run_study(const StudyOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const Ranks ranks = start_ranks();
  const std::string parts_path = study_parts_path(o.output);
  StudyParts done;
  StudyInputs in;
  std::optional<JournalWriter> parts;
  const RootDecision todo = agree_on_items(ranks, "study", [&] { in = load_study_inputs(o); }, [&] {
    RootDecision plan = plan_study(o, in, done);
    if (plan.refusal == 0) parts.emplace(parts_path, o.results_options(), o.resume);
    return plan;
  });
  if (todo.refusal != 0) return todo.refusal;
  std::optional<ProgressLine> progress;
  std::size_t finished = in.parts() - todo.items.size();
  if (ranks.rank == 0) progress.emplace("study");
  ShardedSweep sweep;
  sweep.run = [&](std::int64_t item) { return run_study_part(o, in, item); };
  sweep.record = [&](std::int64_t, const std::string& line, int) {
    const nlohmann::json part = nlohmann::json::parse(line);
    parts->write(part);
    add_study_part(done, part);
    ++finished;
  };
  sweep.tick = [&] {
    progress->update(static_cast<double>(finished), static_cast<double>(in.parts()),
                     std::to_string(finished) + " / " + std::to_string(in.parts()) + " parts on " +
                         std::to_string(ranks.size) + (ranks.size == 1 ? " rank" : " ranks"));
  };
  const SweepStop stop = run_sharded_sweep(ranks, todo.items, sweep);
  if (ranks.rank != 0) return non_root_exit(ranks, stop);
  progress->finish();
  if (stop.signal) {
    std::cerr << "collide2d study: interrupted by " << signal_name(stop.signal) << "; the finished parts are kept in "
              << parts_path << ": the same command with --resume continues\n";
    return interrupted_exit_code(stop.signal);
  }
  if (!stop.errors.empty()) {
    for (const std::string& e : stop.errors) std::cerr << "collide2d study: " << e << "\n";
    std::cerr << "collide2d study: the finished parts are kept in " << parts_path << "\n";
    stop_ranks(ranks);
    return exit_bad_input;
  }
  QueryStudy query_study;
  for (std::size_t k = 0; k < in.units.size(); ++k) add_unit(query_study, done.query_units.at(k));
  std::vector<SceneStudyRun> scene_runs;
  for (const auto& [name, scene] : in.scenes)
    for (const SceneStudyRun& r : done.scenes.at(name)) scene_runs.push_back(r);
  const std::string partial = o.output + ".partial";
  try {
    write_study_file(partial, o, ranks, query_study, in.query_families, scene_runs);
    rename_into_place(partial, o.output);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(partial, ec);
    std::cerr << "collide2d study: " << e.what() << " (finished parts are kept in " << parts_path << ")\n";
    stop_ranks(ranks);
    return exit_bad_input;
  }
  std::filesystem::remove(parts_path);
  stop_ranks(ranks);
  print_study_tables(o, query_study, scene_runs);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\nstudy written to %s in %.1f s on %d %s\n", o.output.c_str(), seconds, ranks.size,
              ranks.size == 1 ? "rank" : "ranks");
  return exit_ok;
}

}  // namespace

Runner add_study_command(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand("study", "Speed against error of every time-of-impact method and mode, per hard family, and "
                                              "step against event engine on scenes; writes HDF5 and prints tables");
  cmd->add_option("-o,--output", o->output, "HDF5 file for the results")->capture_default_str();
  cmd->add_option("--queries", o->queries, "JSON Lines query dataset with oracle answers (collide2d hardset)")
      ->capture_default_str();
  cmd->add_option("--limit-per-family", o->limit_per_family, "use only the first N queries of each family (0: all)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000000));
  cmd->add_option("--repeats", o->repeats, "calls per query for its time")->capture_default_str()->check(CLI::Range(1, 1000));
  cmd->add_option("--scenes", o->scenes, "scene files for the scene level (\"abound\": the built-in scene)")
      ->capture_default_str();
  cmd->add_option("--until", o->until, "simulated seconds per scene run (default: the scene's duration)")
      ->check(finite_positive());
  cmd->add_option("--dt", o->dts, "step sizes of the step engine")->capture_default_str()->check(finite_positive());
  cmd->add_flag("--no-queries", o->no_queries, "skip the query level");
  cmd->add_flag("--no-scenes", o->no_scenes, "skip the scene level");
  cmd->add_flag("--resume", o->resume, "continue an interrupted study from OUTPUT.parts.jsonl (same options)");
  cmd->footer("Under mpirun -n K the parts (each method in each mode, each scene) are shared among the ranks:\n"
              "rank r runs parts r, r + K, ...; rank 0 writes the one file. The results do not depend on K.");
  return [o, cmd] {
    o->command_line = command_line_of(*cmd);
    return run_study(*o);
  };
}

}  // namespace collide2d::cli
