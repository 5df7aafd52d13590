#include "lab/engine_queries.hpp"

#include <stdexcept>

#include "collide2d/scene/builtin_scene.hpp"
#include "collide2d/sim/simulate.hpp"
#include "lab/bench_scenes.hpp"

namespace collide2d {

namespace {

// Told by the engine of every query it asks (EventEngine calls these when its
// observer has them); keeps them until it has enough.
struct QueryRecorder {
  std::vector<ToiQuery>* out = nullptr;
  std::size_t wanted = 0;
  const std::vector<WallGeometry<double>>* walls = nullptr;

  void motion_changed(const World<double>&, int, MotionChange) {}
  void ball_ball_asked(const BallState<double>& a, const BallState<double>& b, double horizon) {
    if (out->size() >= wanted) return;
    ToiQuery q;
    q.kind = QueryKind::ball_ball;
    q.ball = a;
    q.other = b;
    q.horizon = horizon;
    out->push_back(q);
  }
  void ball_wall_asked(const BallState<double>& a, int wall, double horizon) {
    if (out->size() >= wanted) return;
    ToiQuery q;
    q.kind = QueryKind::ball_wall;
    q.ball = a;
    q.wall = (*walls)[static_cast<std::size_t>(wall)].segment;
    q.horizon = horizon;
    out->push_back(q);
  }
};

}  // namespace

const std::vector<std::string>& engine_query_mixes() {
  static const std::vector<std::string> mixes{"engine_gas", "engine_abound"};
  return mixes;
}

Scene engine_mix_scene(const std::string& mix) {
  if (mix == "engine_gas") return hard_disk_gas(1000, 0.45, 1.0, 100.0, 100);
  if (mix == "engine_abound") return scene_from_text(builtin_abound_scene_json());
  throw std::invalid_argument("no engine query mix named '" + mix + "'");
}

std::vector<ToiQuery> engine_queries(const Scene& scene, std::size_t count) {
  std::vector<ToiQuery> out;
  out.reserve(count);
  const World<double> world = make_world<double>(scene);
  while (out.size() < count) {
    const std::size_t before = out.size();
    QueryRecorder recorder{&out, count, &world.walls};
    EventEngine<double, QueryRecorder> engine(world, rest_scales(scene).in<double>(), ToiMethod::analytic, 0.0, false,
                                              recorder);
    // As simulate() runs it: a gas keeps its predictions to the run's end,
    // a scene under accelerations predicts afresh at each record time.
    for (int k = 1; out.size() < count; ++k) {
      const double t = scene.record_interval * k;
      if (t > scene.duration) break;
      engine.run_to(t, scene.duration, [](const Collision<double>&) {});
    }
    if (out.size() == before) throw std::runtime_error("scene '" + scene.name + "' asks no time-of-impact queries");
  }
  return out;
}

}  // namespace collide2d
