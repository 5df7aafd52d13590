// The query level of `collide2d study`: every time-of-impact method in every
// mode over a dataset of queries with the oracle's answers (datasets/hard/),
// per query the time taken and the error, aggregated per family.
//
// Errors, all relative to the query's scale s = max(R, |Δv| H, ½|Δa| H²) and
// judged at τ = 1e-12 s (the analytic strict method's stated bound):
//  - false negative: the oracle's minimum gap is below −τ (a real contact)
//    and the method reports none;
//  - false positive: the method reports a contact, the gap never comes
//    within τ;
//  - error: |true gap at the reported time| / s for a hit (evaluated by the
//    oracle in high precision), |minimum gap| / s for a missed contact, the
//    minimum gap / s for a false positive, 0 for a correct miss;
//  - late report: a contact reported after the true gap has already reached
//    −τ (the first contact passed through: a later one, or a separation);
//    its error is then the depth of the contact it missed;
//  - time error: |t − t_oracle| / H where both report a contact.
// A method "fails its bound" where its error exceeds what it promises:
// analytic 1e-12 (strict) or 1e-7 (fixed) of the scale; bisection its
// tolerance eps plus 1e-12 s; the article's method and the polynomial solver
// promise nothing, judged at 1e-9 s. A false negative or positive, a late
// report or a time outside [0, H] is always outside the bound.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "collide2d/numeric/number_mode.hpp"
#include "lab/oracle.hpp"

namespace collide2d {

struct StudyQuery {
  std::string family;
  ToiQuery query;
  OracleAnswer oracle;
};

// Reads a JSON Lines dataset written by `collide2d hardset` (each line a
// `collide2d toi` query plus "family" and "oracle"); lines without an oracle
// answer get one computed here. `limit_per_family` > 0 keeps only the first
// that many of each family.
std::vector<StudyQuery> read_study_queries(const std::string& path, int limit_per_family);

// A method as the study names it ("analytic", "bisection 1e-6", "seed",
// "eigen companion") and the modes it runs in.
struct StudyMethod {
  std::string name;
  ToiMethod method = ToiMethod::analytic;
  double eps = 0;
  int steps = 1;                   // the horizon cut into this many steps (bisection: the article's dt)
  bool polynomial_solver = false;  // Eigen's companion-matrix solver (strict only)
};
std::vector<StudyMethod> study_methods();

// One row of the query table: a (family, method, mode), or family "all".
struct QueryStudyRow {
  std::string family, method, mode;
  std::int64_t queries = 0, oracle_hits = 0, false_negatives = 0, false_positives = 0, late_reports = 0, over_bound = 0;
  std::int64_t threw = 0;
  double ns_median = 0, ns_p99 = 0, ns_max = 0;
  double error_median = 0, error_p99 = 0, error_max = 0;
  double time_error_median = 0, time_error_p99 = 0, time_error_max = 0;  // NaN if no query hit in both
};

// One method in one mode, query by query (in the order of the dataset).
struct PerQueryResults {
  std::string method, mode;
  std::vector<double> ns, error, time_error;  // NaN where the method threw (time error: also where either missed)
  std::vector<std::int64_t> hit;              // 1 contact reported, 0 none, -1 threw
};

struct QueryStudy {
  std::vector<QueryStudyRow> rows;
  std::vector<PerQueryResults> per_query;
};

// A unit of the query level: one method (an index of study_methods()) in one
// mode, over every query. Units are independent: a sweep shares them among
// ranks (`mpirun collide2d study`), and a study is its units in this order.
struct QueryStudyUnit {
  std::size_t method = 0;
  NumberMode mode = NumberMode::strict;
};
std::vector<QueryStudyUnit> query_study_units();

// One unit's rows (per family, then "all") and its query-by-query results.
struct QueryStudyUnitResult {
  std::vector<QueryStudyRow> rows;
  PerQueryResults per_query;
};
// `progress(queries done)` is called now and then.
QueryStudyUnitResult run_query_study_unit(const std::vector<StudyQuery>& queries, const QueryStudyUnit& unit, int repeats,
                                          const std::function<void(std::size_t)>& progress);
// Appends a unit's results to a study (units must come in order).
void add_unit(QueryStudy& study, QueryStudyUnitResult unit);

// Runs every unit over the queries; each query is timed as the mean of
// `repeats` calls. `progress(done, total)` is called now and then.
QueryStudy run_query_study(const std::vector<StudyQuery>& queries, int repeats,
                           const std::function<void(std::size_t, std::size_t)>& progress);

}  // namespace collide2d
