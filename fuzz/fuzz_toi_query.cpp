// fuzz_toi_query: query lines through what `collide2d toi` runs. The input is
// a JSON Lines file: every non-blank line is parsed (parse_json_text, then
// parse_toi_query), and once all parse, each query is answered by every
// method (analytic, bisection, seed) in both modes (strict, fixed), as
// `collide2d toi --method M --mode X` would answer it; eps is the default
// 1e-9. Each answer is bounded (the solvers cap their iterations), so an
// input costs at most its lines times six solves.
//
// The outcomes the command handles: SceneError while parsing (exit 2 naming
// the line and the field); in fixed mode FixedPointOverflow (exit 2: a value
// outside Q63.64's range), in strict mode StrictOverflow (exit 2: a square of
// a length or speed beyond the double range). Any other exception, a
// sanitizer report or a broken contract below is a finding.
//
// The contract checked (query.md, "Output"): a hit's time lies in
// [0, horizon], in the mode's own numbers (fixed mode holds the horizon
// rounded to 2^-64), and is never NaN.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "collide2d/scene/query_parse.hpp"
#include "collide2d/toi/query.hpp"

namespace {

using namespace collide2d;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_toi_query: %s\n", what.c_str());
  std::abort();
}

void answer_every_way(const ToiQuery& q, std::size_t line) {
  for (const ToiMethod method : {ToiMethod::analytic, ToiMethod::bisection, ToiMethod::seed}) {
    for (const NumberMode mode : all_number_modes) {
      QueryAnswer a;
      double horizon = q.horizon;
      try {
        a = answer_toi_query(q, method, mode, 1e-9);
        if (mode == NumberMode::fixed) horizon = num<Fixed>(q.horizon).to_double();
      } catch (const FixedPointOverflow&) {
        if (mode == NumberMode::fixed) continue;  // toi --mode fixed: exit 2 naming the line
        throw;
      } catch (const StrictOverflow&) {
        if (mode == NumberMode::strict) continue;  // toi --mode strict: exit 2 naming the line
        throw;
      }
      if (a.hit && !(a.t >= 0 && a.t <= horizon))
        finding("line " + std::to_string(line) + ", " + std::string(to_string(mode)) + " mode, method " +
                std::to_string(static_cast<int>(method)) + ": hit at t = " + std::to_string(a.t) +
                " outside [0, " + std::to_string(horizon) + "]");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // As run_toi reads its file: line by line, blank lines skipped, the first
  // refused line ends the command before anything is answered.
  std::vector<ToiQuery> queries;
  std::vector<std::size_t> lines;
  std::size_t start = 0, line = 1;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string one = text.substr(start, end - start);
    start = end + 1;
    if (one.find_first_not_of(" \t\r") != std::string::npos) {
      try {
        queries.push_back(parse_toi_query(parse_json_text(one)));
        lines.push_back(line);
      } catch (const SceneError&) {
        return 0;  // exit 2: "FILE: line N: PATH: MESSAGE"
      }
    }
    ++line;
  }
  for (std::size_t i = 0; i < queries.size(); ++i) answer_every_way(queries[i], lines[i]);
  return 0;
}
