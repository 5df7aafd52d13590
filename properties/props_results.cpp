#include "props_results.hpp"

#include <cmath>
#include <limits>

#include "cli/build_info.hpp"
#include "cli/journal.hpp"
#include "lab/table_file.hpp"
#include "property_table.hpp"

namespace collide2d::properties {

using nlohmann::json;

json PropsPlan::to_json() const {
  json p = json::array();
  for (const auto& [slug, mode] : pairs) p.push_back({slug, mode});
  // The seed as text: JSON numbers beyond 2^53 do not survive every reader.
  return {{"cases", seeds}, {"seed", std::to_string(seed)}, {"max_size", max_size},
          {"max_shrink_tries", max_shrink_tries}, {"pairs", p}};
}

json case_line(std::int64_t c, const PropsCase& d) {
  const CaseOutcome& o = d.outcome;
  return {{"case", c},           {"verdict", o.verdict},     {"detail", o.detail},
          {"balls", o.scene_balls}, {"shrinks", o.shrink_steps}, {"shrink_cut", o.shrink_cut},
          {"counterexample", o.counterexample}, {"reproduce", o.reproduce},
          {"seconds", d.seconds}, {"rank", d.rank}, {"host", d.host}};
}

std::pair<std::int64_t, PropsCase> case_of_line(const json& j) {
  PropsCase d;
  d.outcome.verdict = j.at("verdict");
  d.outcome.detail = j.at("detail");
  d.outcome.scene_balls = j.at("balls");
  d.outcome.shrink_steps = j.at("shrinks");
  d.outcome.shrink_cut = j.at("shrink_cut");
  d.outcome.counterexample = j.at("counterexample");
  d.outcome.reproduce = j.at("reproduce");
  d.seconds = j.at("seconds");
  d.rank = j.at("rank");
  d.host = j.at("host");
  return {j.at("case").get<std::int64_t>(), std::move(d)};
}

json session_line(const PropsSession& s) {
  return {{"session", {{"ranks", s.ranks}, {"cases", s.cases}, {"started", s.started}, {"mpi", s.mpi}}}};
}

PropsJournal read_props_journal(const std::string& path, const PropsPlan& plan) {
  PropsJournal journal;
  cli::read_journal(path, plan.to_json(), [&](const json& line) {
    if (line.contains("session")) {
      const json& s = line["session"];
      journal.sessions.push_back({s.at("ranks"), s.at("cases"), s.at("started"), s.at("mpi")});
      return;
    }
    auto [c, done] = case_of_line(line);
    if (c < 0 || c >= plan.total()) throw std::runtime_error("case " + std::to_string(c) + " is not in the plan");
    journal.cases[c] = std::move(done);
  });
  return journal;
}

namespace {

template <class T, class Get>
std::vector<T> column(const PropsPlan& plan, Get get) {
  std::vector<T> out;
  out.reserve(static_cast<std::size_t>(plan.total()));
  for (std::int64_t c = 0; c < plan.total(); ++c) out.push_back(get(c));
  return out;
}

}  // namespace

void write_props_file(const std::string& path, const PropsPlan& plan, const PropsJournal& journal, bool complete,
                      const std::string& command) {
  TableFile f(path);
  f.attribute("/", "format", std::string("collide2d props 1"));
  f.attribute("/", "complete", static_cast<std::int64_t>(complete ? 1 : 0));
  f.attribute("/", "command", command);
  f.attribute("/", "compiler", cli::compiler_description());

  // What decides the outcomes.
  f.attribute("/parameters", "cases", plan.seeds);
  f.attribute("/parameters", "seed", std::to_string(plan.seed));
  f.attribute("/parameters", "max_size", static_cast<std::int64_t>(plan.max_size));
  f.attribute("/parameters", "max_shrink_tries", static_cast<std::int64_t>(plan.max_shrink_tries));
  f.attribute("/parameters", "case_order",
              std::string("case c: (property, mode) pair c / N of /parameters/pairs, seed index c mod N, N = cases"));
  std::vector<std::string> pair_property, pair_mode;
  for (const auto& [slug, mode] : plan.pairs) pair_property.push_back(slug), pair_mode.push_back(mode);
  f.write("/parameters/pairs/property", pair_property);
  f.write("/parameters/pairs/mode", pair_mode);

  // Case by case, in case order: the same whatever the ranks.
  // Each case's outcome, or null: looked up once, read by every column.
  std::vector<const PropsCase*> outcome(static_cast<std::size_t>(plan.total()), nullptr);
  for (const auto& [c, done] : journal.cases) outcome[static_cast<std::size_t>(c)] = &done;
  const auto find = [&](std::int64_t c) { return outcome[static_cast<std::size_t>(c)]; };
  const std::string t = "/cases/";
  f.write(t + "case", column<std::int64_t>(plan, [](std::int64_t c) { return c; }));
  f.write(t + "property", column<std::string>(plan, [&](std::int64_t c) { return plan.pair(c).first; }));
  f.write(t + "mode", column<std::string>(plan, [&](std::int64_t c) { return plan.pair(c).second; }));
  f.write(t + "seed_index", column<std::int64_t>(plan, [&](std::int64_t c) { return plan.seed_index(c); }));
  f.write(t + "seed", column<std::uint64_t>(plan, [&](std::int64_t c) { return plan.case_seed(c); }));
  f.write(t + "size", column<std::int64_t>(plan, [&](std::int64_t c) { return static_cast<std::int64_t>(plan.case_size(c)); }));
  f.write(t + "verdict", column<std::string>(plan, [&](std::int64_t c) { return find(c) ? find(c)->outcome.verdict : "missing"; }));
  f.write(t + "detail", column<std::string>(plan, [&](std::int64_t c) { return find(c) ? find(c)->outcome.detail : ""; }));
  f.write(t + "scene_balls", column<std::int64_t>(plan, [&](std::int64_t c) -> std::int64_t {
            return find(c) ? find(c)->outcome.scene_balls : -1;
          }));
  f.write(t + "shrink_steps", column<std::int64_t>(plan, [&](std::int64_t c) -> std::int64_t {
            return find(c) ? find(c)->outcome.shrink_steps : -1;
          }));
  f.write(t + "counterexample",
          column<std::string>(plan, [&](std::int64_t c) { return find(c) ? find(c)->outcome.counterexample : ""; }));
  f.write(t + "reproduce", column<std::string>(plan, [&](std::int64_t c) { return find(c) ? find(c)->outcome.reproduce : ""; }));
  std::vector<std::int64_t> missing;
  std::int64_t passed = 0, failed = 0, discarded = 0;
  for (std::int64_t c = 0; c < plan.total(); ++c) {
    const PropsCase* d = find(c);
    if (!d) missing.push_back(c);
    else if (d->outcome.verdict == "pass") ++passed;
    else if (d->outcome.verdict == "fail") ++failed;
    else ++discarded;
  }
  f.write("/missing", missing);
  f.attribute("/", "passed", passed);
  f.attribute("/", "failed", failed);
  f.attribute("/", "discarded", discarded);
  f.attribute("/", "missing", static_cast<std::int64_t>(missing.size()));

  // Where and how long: these depend on the ranks and the machine.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.write("/timing/seconds", column<double>(plan, [&](std::int64_t c) { return find(c) ? find(c)->seconds : nan; }));
  f.write("/timing/rank", column<std::int64_t>(plan, [&](std::int64_t c) -> std::int64_t { return find(c) ? find(c)->rank : -1; }));
  f.write("/timing/host", column<std::string>(plan, [&](std::int64_t c) { return find(c) ? find(c)->host : ""; }));
  std::vector<std::int64_t> ranks, cases;
  std::vector<std::string> started, mpi;
  for (const PropsSession& s : journal.sessions)
    ranks.push_back(s.ranks), cases.push_back(s.cases), started.push_back(s.started), mpi.push_back(s.mpi);
  f.write("/provenance/sessions/ranks", ranks);
  f.write("/provenance/sessions/cases", cases);
  f.write("/provenance/sessions/started", started);
  f.write("/provenance/sessions/mpi", mpi);
  f.attribute("/provenance", "ranks", journal.sessions.empty() ? std::int64_t{1} : journal.sessions.back().ranks);
  f.attribute("/provenance", "sharding",
              std::string("each session lists the cases it runs in case order; rank r of K takes the r-th, (r + K)-th, "
                          "(r + 2K)-th, ... of that list (cli/sharded_sweep.hpp)"));
}

}  // namespace collide2d::properties
