#include "cli/study_parts.hpp"

#include "cli/journal.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace collide2d::cli {
namespace {

using nlohmann::json;

json number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}

double number_of(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (s == "inf") return HUGE_VAL;
  if (s == "-inf") return -HUGE_VAL;
  throw std::runtime_error("not a number: \"" + s + "\"");
}

json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (const double x : v) a.push_back(number(x));
  return a;
}

std::vector<double> numbers_of(const json& j) {
  std::vector<double> v;
  for (const json& x : j) v.push_back(number_of(x));
  return v;
}

json row_json(const QueryStudyRow& r) {
  return {{"family", r.family},
          {"method", r.method},
          {"mode", r.mode},
          {"counts", {r.queries, r.oracle_hits, r.false_negatives, r.false_positives, r.late_reports, r.over_bound, r.threw}},
          {"values", numbers({r.ns_median, r.ns_p99, r.ns_max, r.error_median, r.error_p99, r.error_max,
                              r.time_error_median, r.time_error_p99, r.time_error_max})}};
}

QueryStudyRow row_of(const json& j) {
  QueryStudyRow r;
  r.family = j.at("family");
  r.method = j.at("method");
  r.mode = j.at("mode");
  const auto c = j.at("counts").get<std::vector<std::int64_t>>();
  const auto v = numbers_of(j.at("values"));
  if (c.size() != 7 || v.size() != 9) throw std::runtime_error("a query row of the wrong length");
  std::int64_t* counts[] = {&r.queries, &r.oracle_hits, &r.false_negatives, &r.false_positives, &r.late_reports, &r.over_bound, &r.threw};
  double* values[] = {&r.ns_median, &r.ns_p99, &r.ns_max, &r.error_median, &r.error_p99, &r.error_max,
                      &r.time_error_median, &r.time_error_p99, &r.time_error_max};
  for (int k = 0; k < 7; ++k) *counts[k] = c[k];
  for (int k = 0; k < 9; ++k) *values[k] = v[k];
  return r;
}

json per_query_json(const PerQueryResults& p) {
  return {{"method", p.method}, {"mode", p.mode}, {"ns", numbers(p.ns)}, {"error", numbers(p.error)},
          {"time_error", numbers(p.time_error)}, {"hit", p.hit}};
}

PerQueryResults per_query_of(const json& j) {
  return {j.at("method"), j.at("mode"), numbers_of(j.at("ns")), numbers_of(j.at("error")), numbers_of(j.at("time_error")),
          j.at("hit").get<std::vector<std::int64_t>>()};
}

json run_json(const SceneStudyRun& r) {
  return {{"scene", r.scene},
          {"engine", r.engine},
          {"method", r.method},
          {"mode", r.mode},
          {"values", numbers({r.dt, r.wall_seconds, r.energy_error_max, r.divergence_final, r.growth_rate, r.fit_from,
                              r.fit_to, r.faithful_until, r.deepest_overlap})},
          {"counts", {r.events, r.missed_contacts, r.frames}},
          {"time", numbers(r.time)},
          {"divergence", numbers(r.divergence)},
          {"failure", r.failure}};
}

SceneStudyRun run_of(const json& j) {
  SceneStudyRun r;
  r.scene = j.at("scene");
  r.engine = j.at("engine");
  r.method = j.at("method");
  r.mode = j.at("mode");
  const auto v = numbers_of(j.at("values"));
  const auto c = j.at("counts").get<std::vector<std::int64_t>>();
  if (v.size() != 9 || c.size() != 3) throw std::runtime_error("a scene run of the wrong length");
  double* values[] = {&r.dt, &r.wall_seconds, &r.energy_error_max, &r.divergence_final, &r.growth_rate, &r.fit_from,
                      &r.fit_to, &r.faithful_until, &r.deepest_overlap};
  for (int k = 0; k < 9; ++k) *values[k] = v[k];
  r.events = c[0];
  r.missed_contacts = c[1];
  r.frames = c[2];
  r.time = numbers_of(j.at("time"));
  r.divergence = numbers_of(j.at("divergence"));
  r.failure = j.at("failure");
  return r;
}

}  // namespace

std::string study_parts_path(const std::string& output) { return output + ".parts.jsonl"; }

json query_unit_part(std::size_t unit, const QueryStudyUnitResult& result) {
  json rows = json::array();
  for (const QueryStudyRow& r : result.rows) rows.push_back(row_json(r));
  return {{"part", "query_unit"}, {"unit", unit}, {"rows", rows}, {"per_query", per_query_json(result.per_query)}};
}

json scene_part(const std::string& name, const std::vector<SceneStudyRun>& runs) {
  json a = json::array();
  for (const SceneStudyRun& r : runs) a.push_back(run_json(r));
  return {{"part", "scene"}, {"name", name}, {"runs", a}};
}

void add_study_part(StudyParts& parts, const json& j) {
  const std::string part = j.at("part");
  if (part == "query_unit") {
    QueryStudyUnitResult& unit = parts.query_units[j.at("unit").get<std::size_t>()];
    unit.rows.clear();
    for (const json& r : j.at("rows")) unit.rows.push_back(row_of(r));
    unit.per_query = per_query_of(j.at("per_query"));
  } else if (part == "scene") {
    std::vector<SceneStudyRun>& runs = parts.scenes[j.at("name").get<std::string>()];
    runs.clear();
    for (const json& r : j.at("runs")) runs.push_back(run_of(r));
  } else {
    throw std::runtime_error("unknown part \"" + part + "\"");
  }
}

StudyParts read_study_parts(const std::string& path, const json& options) {
  StudyParts parts;
  read_journal(path, options, [&](const json& line) { add_study_part(parts, line); });
  return parts;
}

}  // namespace collide2d::cli
