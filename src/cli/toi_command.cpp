// collide2d toi QUERIES.jsonl: first contact time of each query, as CSV.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/parse_options.hpp"
#include "collide2d/scene/query_parse.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d::cli {
namespace {

struct ToiOptions {
  std::string queries_path;
  MethodModeEps how;
};

// The first field of a query the fixed-point format cannot hold
// (|x| >= 2^63), as the query line's JSON path, or "".
std::string first_field_outside_fixed_range(const ToiQuery& q) {
  auto outside = [](double x) { return !fixed_range_holds(x); };
  auto ball = [&](const BallState<double>& b, const std::string& at) -> std::string {
    const std::pair<const char*, const Vec2<double>*> fields[] = {
        {".position", &b.position}, {".velocity", &b.velocity}, {".acceleration", &b.acceleration}};
    for (const auto& [name, v] : fields) {
      if (outside(v->x)) return at + name + "[0]";
      if (outside(v->y)) return at + name + "[1]";
    }
    return outside(b.radius) ? at + ".radius" : "";
  };
  if (std::string f = ball(q.ball, "balls[0]"); !f.empty()) return f;
  if (q.kind == QueryKind::ball_ball) return ball(q.other, "balls[1]");
  for (const auto& [name, p] : {std::pair{"walls[0].a", &q.wall.a}, {"walls[0].b", &q.wall.b}}) {
    if (outside(p->x)) return std::string(name) + "[0]";
    if (outside(p->y)) return std::string(name) + "[1]";
  }
  return outside(q.horizon) ? "horizon" : "";
}

// Every line is read and checked before anything is computed, so a bad line
// costs no output: one message naming the file, the line and the field.
int run_toi(const ToiOptions& o) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (o.queries_path != "-") {
    std::error_code ec;
    if (std::filesystem::is_directory(o.queries_path, ec)) {
      std::cerr << o.queries_path << ": is a directory, not a query file\n";
      return exit_bad_input;
    }
    file.open(o.queries_path);
    if (!file) {
      std::cerr << o.queries_path << ": cannot open file\n";
      return exit_bad_input;
    }
    in = &file;
  }
  std::vector<ToiQuery> queries;
  std::vector<int> line_numbers;
  std::string text;
  for (int line = 1; std::getline(*in, text); ++line) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank lines are not queries
    try {
      queries.push_back(parse_toi_query(parse_json_text(text)));
      line_numbers.push_back(line);
      if (o.how.number_mode() == NumberMode::fixed)
        if (const std::string field = first_field_outside_fixed_range(queries.back()); !field.empty())
          throw SceneError(field, "outside the fixed-point range (about ±9.2e18); --mode strict answers it");
    } catch (const SceneError& e) {
      std::cerr << o.queries_path << ": line " << line << ": " << e.what() << "\n";
      return exit_bad_input;
    }
  }
  if (in->bad()) {
    std::cerr << o.queries_path << ": cannot read the file\n";
    return exit_bad_input;
  }
  std::string out = "index,hit,t\n";
  char row[64];
  for (std::size_t i = 0; i < queries.size(); ++i) {
    QueryAnswer a;
    try {
      a = answer_toi_query(queries[i], o.how.toi_method(), o.how.number_mode(), o.how.eps);
    } catch (const FixedPointOverflow& e) {
      std::cerr << o.queries_path << ": line " << line_numbers[i] << ": " << e.what()
                << " (an intermediate value of this query's time of impact leaves the fixed format's range, about ±9.2e18)\n";
      return exit_bad_input;
    } catch (const StrictOverflow& e) {
      std::cerr << o.queries_path << ": line " << line_numbers[i] << ": " << e.what()
                << " (the squares of this query's lengths and speeds exceed the double range, about 1e308)\n";
      return exit_bad_input;
    }
    if (a.hit)
      std::snprintf(row, sizeof row, "%zu,1,%.17g\n", i, a.t);
    else
      std::snprintf(row, sizeof row, "%zu,0,\n", i);
    out += row;
  }
  std::cout << out;
  return exit_ok;
}

}  // namespace

Runner add_toi_command(CLI::App& app) {
  auto options = std::make_shared<ToiOptions>();
  CLI::App* cmd = app.add_subcommand("toi", "time of first contact for each query of a JSON Lines file, as CSV "
                                            "index,hit,t (t with 17 significant digits)");
  cmd->add_option("QUERIES", options->queries_path,
                  "JSON Lines file, one scene per line with one moving ball and one wall or one more ball, "
                  "plus \"horizon\"; - reads standard input")
      ->required();
  add_method_mode_eps(*cmd, options->how);
  return [options] { return run_toi(*options); };
}

}  // namespace collide2d::cli
