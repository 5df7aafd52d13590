#include "lab/query_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <nlohmann/json.hpp>

#include "collide2d/scene/query_parse.hpp"
#include "lab/polynomial_baseline.hpp"

namespace collide2d {

std::vector<StudyQuery> read_study_queries(const std::string& path, int limit_per_family) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<StudyQuery> out;
  std::map<std::string, int> count;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.empty()) continue;
    try {
      const nlohmann::json j = nlohmann::json::parse(text);
      StudyQuery s;
      s.family = j.value("family", std::string("unnamed"));
      if (limit_per_family > 0 && count[s.family] >= limit_per_family) continue;
      s.query = parse_toi_query(j);
      if (j.contains("oracle")) {
        const nlohmann::json& o = j["oracle"];
        s.oracle = {o.at("hit").get<bool>(), o.at("t").get<double>(), o.at("min_gap").get<double>(), o.at("scale").get<double>()};
      } else {
        s.oracle = oracle_time_of_impact(s.query);
      }
      ++count[s.family];
      out.push_back(std::move(s));
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": line " + std::to_string(line) + ": " + e.what());
    }
  }
  if (out.empty()) throw std::runtime_error(path + ": no queries");
  return out;
}

std::vector<StudyMethod> study_methods() {
  // Bisection over the whole horizon (one step, as the article's simulator
  // with dt = H), and with the horizon cut into 64 steps (dt = H/64).
  return {{"analytic", ToiMethod::analytic, 0, 1, false},
          {"bisection 1e-3", ToiMethod::bisection, 1e-3, 1, false},
          {"bisection 1e-6", ToiMethod::bisection, 1e-6, 1, false},
          {"bisection 1e-9", ToiMethod::bisection, 1e-9, 1, false},
          {"bisection 1e-9 H/64", ToiMethod::bisection, 1e-9, 64, false},
          {"seed", ToiMethod::seed, 1e-9, 1, false},
          {"eigen companion", ToiMethod::analytic, 0, 1, true}};
}

namespace {

struct Outcome {
  bool threw = false, hit = false;
  double t = 0, ns = 0;
};

// Times `repeats` calls of solve() and keeps the last answer.
template <class Solve>
Outcome timed(int repeats, Solve solve) {
  Outcome o;
  try {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r) {
      const auto [hit, t] = solve();
      o.hit = hit;
      o.t = t;
      // Keep every call: the result escapes to memory the compiler cannot see.
      asm volatile("" : : "r"(&o) : "memory");
    }
    o.ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / repeats;
  } catch (const std::exception&) {
    o.threw = true;
  }
  return o;
}

template <class Num>
BallState<Num> advanced(const BallState<Num>& b, const Num& t) {
  return {position_at(b, t), b.velocity + t * b.acceleration, b.acceleration, b.radius};
}

// The method over `steps` equal steps of the horizon, each starting from the
// exact state at its start; the first step with a contact answers.
template <class Num>
ToiResult<Num> solve_in_steps(const ToiQueryOf<Num>& q, const StudyMethod& m, const Num& eps) {
  if (m.steps == 1) return solve_toi_query(q, m.method, eps);
  const Num h = q.horizon / num<Num>(m.steps);
  ToiQueryOf<Num> part = q;
  part.horizon = h;
  for (int k = 0; k < m.steps; ++k) {
    const Num t0 = h * num<Num>(k);
    if (k + 1 == m.steps) part.horizon = q.horizon - t0;  // no rounding gap before H
    part.ball = advanced(q.ball, t0);
    part.other = advanced(q.other, t0);
    ToiResult<Num> r = solve_toi_query(part, m.method, eps);
    if (r.hit()) {
      r.time = t0 + r.time;
      return r;
    }
  }
  return {};
}

template <class Num>
Outcome answer(const ToiQueryOf<Num>& q, const StudyMethod& m, int repeats) {
  const Num eps = num<Num>(m.eps);
  return timed(repeats, [&] {
    const ToiResult<Num> r = solve_in_steps(q, m, eps);
    return std::pair<bool, double>{r.hit(), NumberTraits<Num>::to_double(r.time)};
  });
}

Outcome answer_polynomial(const ToiQuery& q, int repeats) {
  return timed(repeats, [&] {
    const ToiResult<double> r = q.kind == QueryKind::ball_wall ? polynomial_solver_ball_wall(q.ball, q.wall, q.horizon)
                                                               : polynomial_solver_ball_ball(q.ball, q.other, q.horizon);
    return std::pair<bool, double>{r.hit(), r.time};
  });
}

// What a method promises, relative to the scale (see query_study.hpp).
double stated_bound(const StudyMethod& m, NumberMode mode, double scale) {
  if (m.polynomial_solver || m.method == ToiMethod::seed) return 1e-9;
  if (m.method == ToiMethod::bisection) return m.eps / scale + 1e-12;
  return mode == NumberMode::strict ? 1e-12 : 1e-7;
}

struct Measured {
  double ns = 0, error = 0, time_error = std::numeric_limits<double>::quiet_NaN();
  bool threw = false, hit = false, oracle_hit = false, false_negative = false, false_positive = false, late = false;
  bool over_bound = false;
};

// The first time the true gap reaches −τ: a reported contact after it has
// passed through the first one (a later contact, or a separation). Found by
// the oracle once per query, when a method first needs it.
struct FirstDeepContact {
  bool known = false, exists = false;
  double t = 0;
};

Measured judge(const StudyQuery& s, const Outcome& o, const StudyMethod& m, NumberMode mode, FirstDeepContact& deep) {
  Measured r;
  r.ns = o.ns;
  r.threw = o.threw;
  const double scale = s.oracle.scale, tau = 1e-12 * scale;
  r.oracle_hit = s.oracle.min_gap < -tau;
  if (o.threw) return r;
  r.hit = o.hit;
  r.false_negative = r.oracle_hit && !o.hit;
  r.false_positive = o.hit && s.oracle.min_gap > tau;
  if (o.hit) {
    r.error = abs(oracle_gap_at(s.query, Reference(o.t))).convert_to<double>() / scale;
    if (s.oracle.hit) r.time_error = std::fabs(o.t - s.oracle.t) / s.query.horizon;
  } else if (r.false_negative) {
    r.error = -s.oracle.min_gap / scale;
  }
  if (r.false_positive) r.error = std::max(r.error, s.oracle.min_gap / scale);
  if (o.hit && r.oracle_hit) {
    if (!deep.known) {
      const auto t = oracle_first_time_gap_at_most(s.query, Reference(-tau));
      deep = {true, t.has_value(), t ? t->convert_to<double>() : 0.0};
    }
    // Past the first contact: it was missed, however small the gap at t.
    r.late = deep.exists && deep.t < o.t;
    if (r.late) r.error = std::max(r.error, -s.oracle.min_gap / scale);
  }
  const bool outside = o.hit && !(o.t >= 0 && o.t <= s.query.horizon);
  r.over_bound = r.false_negative || r.false_positive || r.late || outside || r.error > stated_bound(m, mode, scale);
  return r;
}

double quantile(std::vector<double> v, double p) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t i = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size()))) - (p > 0 ? 1 : 0);
  return v[std::min(i, v.size() - 1)];
}

QueryStudyRow aggregate(const std::string& family, const std::string& method, NumberMode mode,
                        const std::vector<Measured>& ms) {
  QueryStudyRow row{family, method, std::string(to_string(mode))};
  std::vector<double> ns, error, time_error;
  for (const Measured& m : ms) {
    ++row.queries;
    row.oracle_hits += m.oracle_hit;
    if (m.threw) {
      ++row.threw;
      continue;
    }
    row.false_negatives += m.false_negative;
    row.false_positives += m.false_positive;
    row.late_reports += m.late;
    row.over_bound += m.over_bound;
    ns.push_back(m.ns);
    error.push_back(m.error);
    time_error.push_back(m.time_error);
  }
  row.ns_median = quantile(ns, 0.5), row.ns_p99 = quantile(ns, 0.99), row.ns_max = quantile(ns, 1.0);
  row.error_median = quantile(error, 0.5), row.error_p99 = quantile(error, 0.99), row.error_max = quantile(error, 1.0);
  row.time_error_median = quantile(time_error, 0.5), row.time_error_p99 = quantile(time_error, 0.99);
  row.time_error_max = quantile(time_error, 1.0);
  return row;
}

template <class Num>
using Converted = std::vector<std::optional<ToiQueryOf<Num>>>;

template <class Num>
Converted<Num> converted_queries(const std::vector<StudyQuery>& queries) {
  Converted<Num> out;
  for (const StudyQuery& s : queries) {
    try {
      out.push_back(convert_query<Num>(s.query));
    } catch (const std::exception&) {  // outside the type's range
      out.emplace_back();
    }
  }
  return out;
}

}  // namespace

std::vector<QueryStudyUnit> query_study_units() {
  std::vector<QueryStudyUnit> units;
  const std::vector<StudyMethod> methods = study_methods();
  for (std::size_t k = 0; k < methods.size(); ++k)
    for (const NumberMode mode : {NumberMode::strict, NumberMode::fixed})
      if (!(methods[k].polynomial_solver && mode == NumberMode::fixed))  // Eigen's solver is double only
        units.push_back({k, mode});
  return units;
}

QueryStudyUnitResult run_query_study_unit(const std::vector<StudyQuery>& queries, const QueryStudyUnit& unit, int repeats,
                                          const std::function<void(std::size_t)>& progress) {
  std::vector<std::string> families;
  for (const StudyQuery& s : queries)
    if (std::find(families.begin(), families.end(), s.family) == families.end()) families.push_back(s.family);
  const StudyMethod m = study_methods().at(unit.method);
  const NumberMode mode = unit.mode;
  // The queries in the unit's number type, converted once (not timed); a
  // query outside the type's range is empty there and counted as threw.
  std::vector<FirstDeepContact> deep(queries.size());  // the oracle's, found when first needed
  std::vector<Measured> measured(queries.size());
  with_number_type(mode, [&](auto type) {
    using Num = typename decltype(type)::type;
    const Converted<Num> converted = m.polynomial_solver ? Converted<Num>{} : converted_queries<Num>(queries);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      Outcome o;
      if (m.polynomial_solver) o = answer_polynomial(queries[i].query, repeats);
      else if (converted[i]) o = answer(*converted[i], m, repeats);
      else o.threw = true;
      measured[i] = judge(queries[i], o, m, mode, deep[i]);
      if ((i + 1) % 500 == 0) progress(i + 1);
    }
  });
  QueryStudyUnitResult out;
  for (const std::string& family : families) {
    std::vector<Measured> part;
    for (std::size_t i = 0; i < queries.size(); ++i)
      if (queries[i].family == family) part.push_back(measured[i]);
    out.rows.push_back(aggregate(family, m.name, mode, part));
  }
  out.rows.push_back(aggregate("all", m.name, mode, measured));
  out.per_query.method = m.name;
  out.per_query.mode = std::string(to_string(mode));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Measured& x : measured) {
    out.per_query.ns.push_back(x.threw ? nan : x.ns);
    out.per_query.error.push_back(x.threw ? nan : x.error);
    out.per_query.time_error.push_back(x.time_error);
    out.per_query.hit.push_back(x.threw ? -1 : x.hit ? 1 : 0);
  }
  return out;
}

void add_unit(QueryStudy& study, QueryStudyUnitResult unit) {
  for (QueryStudyRow& r : unit.rows) study.rows.push_back(std::move(r));
  study.per_query.push_back(std::move(unit.per_query));
}

QueryStudy run_query_study(const std::vector<StudyQuery>& queries, int repeats,
                           const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::vector<QueryStudyUnit> units = query_study_units();
  const std::size_t total = units.size() * queries.size();
  QueryStudy study;
  for (std::size_t u = 0; u < units.size(); ++u)
    add_unit(study, run_query_study_unit(queries, units[u], repeats,
                                         [&](std::size_t n) { progress(u * queries.size() + n, total); }));
  progress(total, total);
  return study;
}

}  // namespace collide2d
