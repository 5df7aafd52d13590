#include "collide2d/scene/query_parse.hpp"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace collide2d {

ToiQuery parse_toi_query(const nlohmann::json& line) {
  if (!line.is_object()) throw SceneError("", "a query line must be a JSON object");
  ToiQuery q;
  const auto h = line.find("horizon");
  if (h == line.end()) throw SceneError("horizon", "missing");
  if (!h->is_number() || !std::isfinite(h->get<double>())) throw SceneError("horizon", "must be a finite number");
  q.horizon = h->get<double>();
  if (!(q.horizon >= 0)) throw SceneError("horizon", "must be >= 0");

  ParseOptions options;
  options.ignore_unknown_top_level_keys = true;
  const Scene s = parse_scene(line, options);
  check_no_initial_overlap(s);

  auto state = [&](const BallSpec& b) {
    const Point acc = effective_acceleration(s, b);
    return BallState<double>{{b.position[0], b.position[1]}, {b.velocity[0], b.velocity[1]}, {acc[0], acc[1]}, b.radius};
  };
  if (s.balls.size() == 1 && s.walls.size() == 1) {
    if (s.balls[0].fixed) throw SceneError("balls[0].fixed", "the query's ball must move");
    q.kind = QueryKind::ball_wall;
    q.ball = state(s.balls[0]);
    q.wall = {{s.walls[0].a[0], s.walls[0].a[1]}, {s.walls[0].b[0], s.walls[0].b[1]}};
    return q;
  }
  if (s.balls.size() == 2 && s.walls.empty()) {
    if (s.balls[0].fixed && s.balls[1].fixed) throw SceneError("balls", "both balls are fixed: nothing moves");
    const bool swap = s.balls[0].fixed;  // the moving ball comes first in the answer
    q.kind = QueryKind::ball_ball;
    q.ball = state(s.balls[swap ? 1 : 0]);
    q.other = state(s.balls[swap ? 0 : 1]);
    return q;
  }
  throw SceneError(s.balls.size() > 2 || s.walls.size() > 1 ? (s.balls.size() > 2 ? "balls" : "walls") : "balls",
                   "a query holds one moving ball and either one wall or one more ball (found " +
                       std::to_string(s.balls.size()) + " balls, " + std::to_string(s.walls.size()) + " walls)");
}

}  // namespace collide2d
