#include "lab/scene_study.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "collide2d/sim/simulate.hpp"
#include "lab/reference.hpp"

namespace collide2d {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct Recorded {
  std::vector<FrameRecord> frames;
  SimulationSummary summary;
  std::int64_t events = 0;
};

// Fills r as the run goes, so a run that throws (a stall, an overflow)
// leaves what it managed.
template <class Num>
void record(Recorded& r, const Scene& scene, double until, const EngineChoice& choice) {
  auto on_frame = [&](const FrameRecord& f) { r.frames.push_back(f); };
  auto on_event = [&](const EventRecord&) { ++r.events; };
  const auto start = std::chrono::steady_clock::now();
  try {
    r.summary = simulate<Num>(scene, until, on_frame, on_event, choice);
  } catch (...) {
    r.summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    throw;
  }
}

// log d = a + λ t by least squares over the frames where d lies in
// [lo, hi]; {λ, first t, last t}, NaN with fewer than 3 such frames.
std::array<double, 3> fit_growth(const std::vector<double>& t, const std::vector<double>& d, double lo, double hi) {
  double n = 0, st = 0, sl = 0, stt = 0, stl = 0, from = nan, to = nan;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!(d[i] >= lo && d[i] <= hi)) continue;
    const double l = std::log(d[i]);
    n += 1, st += t[i], sl += l, stt += t[i] * t[i], stl += t[i] * l;
    if (std::isnan(from)) from = t[i];
    to = t[i];
  }
  const double denominator = n * stt - st * st;
  if (n < 3 || !(denominator > 0)) return {nan, nan, nan};
  return {(n * stl - st * sl) / denominator, from, to};
}

SceneStudyRun compare(const std::string& name, const Scene& scene, const Recorded& run, const Recorded& reference) {
  SceneStudyRun out;
  out.scene = name;
  out.wall_seconds = run.summary.wall_seconds;
  out.events = run.events;
  out.missed_contacts = run.summary.wall_crossings;
  out.deepest_overlap = run.summary.deepest_overlap;
  const std::size_t frames = std::min(run.frames.size(), reference.frames.size());
  out.frames = static_cast<std::int64_t>(frames);
  const double e0 = std::fabs(reference.frames.front().energy);
  for (std::size_t k = 0; k < frames; ++k) {
    const FrameRecord &x = run.frames[k], &y = reference.frames[k];
    double sum = 0;
    for (std::size_t i = 0; i < x.position.size(); ++i) sum += (x.position[i] - y.position[i]) * (x.position[i] - y.position[i]);
    out.time.push_back(y.time);
    out.divergence.push_back(std::sqrt(sum / static_cast<double>(scene.balls.size())));
    out.energy_error_max = std::max(out.energy_error_max, std::fabs(x.energy - y.energy) / (e0 > 0 ? e0 : 1.0));
  }
  out.divergence_final = out.divergence.empty() ? 0 : out.divergence.back();
  double r_min = std::numeric_limits<double>::infinity();
  for (const BallSpec& b : scene.balls) r_min = std::min(r_min, b.radius);
  const auto [rate, from, to] = fit_growth(out.time, out.divergence, 1e-12 * r_min, 1e-2 * r_min);
  out.growth_rate = rate, out.fit_from = from, out.fit_to = to;
  out.faithful_until = nan;
  for (std::size_t k = 0; k < out.time.size(); ++k)
    if (out.divergence[k] > 1e-3 * r_min) {
      out.faithful_until = out.time[k];
      break;
    }
  return out;
}

}  // namespace

std::vector<SceneStudyRun> run_scene_study(const std::string& name, const Scene& scene, double until,
                                           const std::vector<double>& dts,
                                           const std::function<void(const std::string&)>& progress) {
  struct Spec {
    std::string engine, method;
    NumberMode mode;
    EngineChoice choice;
  };
  std::vector<Spec> specs = {{"event", "analytic", NumberMode::strict, {}}, {"event", "analytic", NumberMode::fixed, {}}};
  for (const double dt : dts) {
    specs.push_back({"step", "bisection 1e-9", NumberMode::strict, {true, dt, ToiMethod::bisection, 1e-9}});
    specs.push_back({"step", "bisection 1e-9", NumberMode::fixed, {true, dt, ToiMethod::bisection, 1e-9}});
    specs.push_back({"step", "seed", NumberMode::strict, {true, dt, ToiMethod::seed, 1e-9}});
  }
  std::vector<SceneStudyRun> runs;
  progress(name + ": reference (event engine in " + std::to_string(std::numeric_limits<Reference>::digits10) +
           "-digit arithmetic)");
  Recorded reference;
  record<Reference>(reference, scene, until, {});
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const Spec& s = specs[i];
    char dt_text[32];
    std::snprintf(dt_text, sizeof dt_text, "%g", s.choice.dt);
    progress(name + ": " + s.engine + " " + s.method + " " + std::string(to_string(s.mode)) +
             (s.choice.step ? " dt " + std::string(dt_text) : "") + " (" + std::to_string(i + 1) + "/" +
             std::to_string(specs.size()) + ")");
    Recorded r;
    std::string failure;
    try {
      with_number_type(s.mode, [&](auto type) { record<typename decltype(type)::type>(r, scene, until, s.choice); });
    } catch (const std::exception& e) {
      // A run the engine refuses is a finding too: reported with what it
      // managed (its frames up to the failure), never hidden.
      failure = e.what();
      progress(name + ": run failed: " + failure);
      if (r.frames.empty()) r.frames.push_back(reference.frames.front());
    }
    SceneStudyRun run = compare(name, scene, r, reference);
    run.engine = s.engine, run.method = s.method, run.mode = std::string(to_string(s.mode)), run.dt = s.choice.dt;
    run.failure = failure;
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace collide2d
