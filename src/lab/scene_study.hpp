// The scene level of `collide2d study`: the step engine over a sweep of step
// sizes and the event engine, each against a reference run of the same
// scene: the event engine in the high-precision type (lab/reference.hpp,
// 60 digits), the exact dynamics as far as any run here can tell.
//
// Per run: wall time, events, the energy error against the reference
// (max over frames of |E(t) − E_ref(t)| / |E_ref(0)|: the reference's own
// losses, restitution and rest, cancel), contacts missed (a centre through a
// wall) and the deepest overlap, and the trajectory divergence from the
// reference at every frame: the RMS over balls of |x(t) − x_ref(t)|. A gas
// is chaotic: a divergence grows like e^{λt} whatever its source, so λ is
// fitted (least squares on log divergence) where it lies between 1e-12 and
// 1e-2 of the smallest radius, before it saturates; the time a run stays
// within a tolerance δ of the exact dynamics is then about ln(δ/δ₀)/λ.
// `faithful_until` is the measured one for δ = 1e-3 r_min: the first frame
// at which the divergence exceeds it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "collide2d/scene/scene.hpp"
#include "collide2d/toi/query.hpp"

namespace collide2d {

struct SceneStudyRun {
  std::string scene, engine, method, mode;
  double dt = 0;  // 0: the event engine
  double wall_seconds = 0, energy_error_max = 0, divergence_final = 0;
  double growth_rate = 0, fit_from = 0, fit_to = 0;  // NaN when there is nothing to fit
  double faithful_until = 0;  // first time the divergence exceeds 1e-3 of the smallest radius (NaN: never)
  std::int64_t events = 0, missed_contacts = 0, frames = 0;
  double deepest_overlap = 0;
  std::vector<double> time, divergence;  // per frame
  std::string failure;                   // why the run stopped early ("" if it did not)
};

// Every run of one scene up to `until`: the event engine in both modes, the
// step engine with bisection (tolerance 1e-9) in both modes and with the
// article's seed method in strict mode, at every dt of `dts`.
// `progress(message)` is called before each run.
std::vector<SceneStudyRun> run_scene_study(const std::string& name, const Scene& scene, double until,
                                           const std::vector<double>& dts,
                                           const std::function<void(const std::string&)>& progress);

}  // namespace collide2d
