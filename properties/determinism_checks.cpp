// Determinism, run-file replay, resume, and fixed against strict
// (scene_checks.hpp).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "check_support.hpp"
#include "collide2d/io/run_file.hpp"
#include "scene_checks.hpp"
#include "scene_json.hpp"
#include "scene_scales.hpp"

namespace collide2d::properties {
namespace {

struct Run {
  std::vector<FrameRecord> frames;
  std::vector<EventRecord> events;
  SimulationSummary summary;
};

// A run, stopped by the scene's event cap (event_cap.hpp) if it runs away.
template <class Num>
Run run(const Scene& scene, double until, const CheckpointControl& checkpoints = {}, const EngineChoice& choice = {}) {
  Run r;
  EventCount cap(event_cap(scene, until));
  r.summary = simulate<Num>(scene, until, [&](const FrameRecord& f) { r.frames.push_back(f); },
                            [&](const EventRecord& e) { r.events.push_back(e), cap.collision(e.time); }, choice,
                            checkpoints);
  return r;
}

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }
bool same_bits(const std::vector<double>& x, const std::vector<double>& y) {
  return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
}

// The first difference between two frame sequences (from frame `first` of
// `a` and of `b` on), or "".
std::string frame_difference(const std::vector<FrameRecord>& a, std::size_t first_a, const std::vector<FrameRecord>& b,
                             std::size_t first_b) {
  if (a.size() - first_a != b.size() - first_b)
    return "frame counts differ: " + std::to_string(a.size() - first_a) + " and " + std::to_string(b.size() - first_b);
  for (std::size_t k = 0; first_a + k < a.size(); ++k) {
    const FrameRecord &x = a[first_a + k], &y = b[first_b + k];
    if (x.state_hash != y.state_hash || !same_bits(x.position, y.position) || !same_bits(x.velocity, y.velocity) ||
        !same_bits(x.energy, y.energy) || x.position_raw != y.position_raw || x.velocity_raw != y.velocity_raw)
      return "frame " + std::to_string(x.step) + " (t = " + g17(x.time) + ") differs";
  }
  return "";
}

std::string event_difference(const std::vector<EventRecord>& a, std::size_t first_a, const std::vector<EventRecord>& b) {
  if (a.size() - first_a != b.size())
    return "event counts differ: " + std::to_string(a.size() - first_a) + " and " + std::to_string(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    const EventRecord &x = a[first_a + k], &y = b[k];
    if (!same_bits(x.time, y.time) || x.kind != y.kind || x.a != y.a || x.b != y.b || !same_bits(x.impulse, y.impulse))
      return "event " + std::to_string(first_a + k) + " differs (t = " + g17(x.time) + " and " + g17(y.time) + ")";
  }
  return "";
}

template <class Num>
CheckResult deterministic(const Scene& scene, double duration) {
  const Run a = run<Num>(scene, duration), b = run<Num>(scene, duration);
  if (auto d = frame_difference(a.frames, 0, b.frames, 0); !d.empty()) return "two runs: " + d;
  if (auto d = event_difference(a.events, 0, b.events); !d.empty()) return "two runs: " + d;
  return std::nullopt;
}

// Writes the run with the library's RunWriter, reads it back, rebuilds the
// scene from the file's own scene JSON (scene_to_json → parse_scene) and
// simulates again: frames (with raw fixed values) and events must be the
// file's, bit for bit. Exactly what `collide2d replay` relies on.
template <class Num>
CheckResult run_file_replay(const Scene& scene, double duration) {
  static std::atomic<int> counter{0};
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("collide2d-property-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".h5");
  const Run original = run<Num>(scene, duration);
  RunHeader header;
  header.scene_json = scene_to_json(scene);
  header.options_json = "{}";
  header.mode = std::is_same_v<Num, Fixed> ? "fixed" : "strict";
  for (const BallSpec& b : scene.balls) header.radius.push_back(b.radius), header.mass.push_back(b.mass);
  for (const WallSpec& w : scene.walls) header.walls.push_back({w.a[0], w.a[1], w.b[0], w.b[1]});
  header.creator_version = "property";
  header.compiler = "-";
  header.author = "collide2d properties";
  RunContents back;
  try {
    RunWriter writer(path.string(), header);
    for (const FrameRecord& f : original.frames)
      writer.append_frame({f.step, f.time, f.position, f.velocity, f.energy, f.state_hash, f.position_raw, f.velocity_raw});
    for (const EventRecord& e : original.events) writer.append_event(e);
    writer.finish("{}");
    back = read_run_file(path.string());
  } catch (...) {
    std::filesystem::remove(path);
    throw;
  }
  std::filesystem::remove(path);
  const Scene reread = parse_scene(parse_json_text(back.header.scene_json));
  const Run replayed = run<Num>(reread, duration);
  if (auto d = frame_difference(back.frames, 0, replayed.frames, 0); !d.empty()) return "replay from the run file: " + d;
  if (auto d = event_difference(back.events, 0, replayed.events); !d.empty()) return "replay from the run file: " + d;
  return std::nullopt;
}

// A checkpoint after every frame; resuming from the middle one must give the
// uninterrupted run's remaining frames and events, bit for bit, and the same
// checkpoints after it, byte for byte: a resumed run is itself checkpointed
// and resumed, and its file must equal an uninterrupted run's (kill_resume.sh).
// The bytes catch state that decides no motion but the bookkeeping a later
// resume continues (a cell's member order once decided the queue's push
// numbers there, and a resumed gas's checkpoints differed from t = 1255 on).
template <class Num>
CheckResult resume_equals_uninterrupted(const Scene& scene, double duration) {
  struct Saved {
    std::vector<std::uint8_t> state;
    std::size_t frames, events;
  };
  std::vector<Saved> saved;
  Run whole;
  CheckpointControl every;
  every.every_frames = 1;
  every.on_checkpoint = [&](double, std::vector<std::uint8_t> state) {
    saved.push_back({std::move(state), whole.frames.size(), whole.events.size()});
  };
  EventCount cap(event_cap(scene, duration));
  whole.summary = simulate<Num>(scene, duration, [&](const FrameRecord& f) { whole.frames.push_back(f); },
                                [&](const EventRecord& e) { whole.events.push_back(e), cap.collision(e.time); }, {},
                                every);
  const Run plain = run<Num>(scene, duration);
  if (auto d = frame_difference(whole.frames, 0, plain.frames, 0); !d.empty()) return "with and without checkpoints: " + d;
  if (saved.empty()) return std::nullopt;
  const std::size_t middle_index = saved.size() / 2;
  const Saved& middle = saved[middle_index];
  std::vector<std::vector<std::uint8_t>> saved_after;
  CheckpointControl resume;
  resume.resume_from = &middle.state;
  resume.every_frames = 1;
  resume.on_checkpoint = [&](double, std::vector<std::uint8_t> state) { saved_after.push_back(std::move(state)); };
  const Run rest = run<Num>(scene, duration, resume);
  const std::string at = "resumed at frame " + std::to_string(middle.frames) + ": ";
  if (auto d = frame_difference(whole.frames, middle.frames, rest.frames, 0); !d.empty()) return at + d;
  if (auto d = event_difference(whole.events, middle.events, rest.events); !d.empty()) return at + d;
  if (whole.summary.final_hash != rest.summary.final_hash) return at + "the run ends in another state";
  if (saved_after.size() != saved.size() - middle_index - 1)
    return at + std::to_string(saved_after.size()) + " checkpoints after it, the uninterrupted run has " +
           std::to_string(saved.size() - middle_index - 1);
  for (std::size_t k = 0; k < saved_after.size(); ++k)
    if (saved_after[k] != saved[middle_index + 1 + k].state)
      return at + "checkpoint " + std::to_string(middle_index + 1 + k) + " differs from the uninterrupted run's";
  return std::nullopt;
}

// Fixed against strict on a short horizon.
// Both run the same exact motion model; they differ by rounding. Strict
// rounds far more coarsely (eps relative against 2^-64 absolute), so the
// difference is the strict error: δ0 = 64 eps (P + V T + A T²) at the
// start of the run and again at every event (the same per-step rounding as in
// the energy bound, in lengths). A collision with a curved surface (another
// ball, a fixed ball, a wall's end; radius ≥ r_min) turns a position error
// δ into a direction error ≤ 2 δ / r_min, which grows into a position error
// ≤ 2 δ V T / r_min by the end: factor G = 2 + 4 V T / r_min per such
// collision (the disk-scattering Lyapunov growth, with ℓ ≤ V T). A flat wall
// keeps the error (factor 1). So
//     |x_fixed − x_strict| ≤ δ0 · (1 + events) · G^(collisions with curved surfaces).
// This grows exponentially with events (the dynamics are chaotic): the
// property is only meaningful for short horizons with few events, and it is
// run so (scene_properties.cpp). Events are compared as (kind, a, b) in order.
// The collapse and resting-contact rules are not claimed: each is a
// threshold decision (rest, creep, the TC window), or not Lipschitz in the
// state (a hop's speed goes as sqrt(n·Δa), and a pair touching with a tilt δ
// has n·Δa ∝ δ), so a rounding difference can change its outcome by far more
// than the bound. The check does not apply (NotApplicable: the case is
// discarded, never counted as a pass) to inelastic scenes and to runs in
// which any rule acted in either mode.
CheckResult fixed_matches_strict(const Scene& scene, double duration) {
  for (std::size_t i = 0; i < scene.balls.size(); ++i)
    if (scene.balls[i].restitution != 1)
      throw NotApplicable("inelastic: restitution " + g17(scene.balls[i].restitution) + " at balls[" + std::to_string(i) + "]");
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    if (scene.walls[w].restitution != 1)
      throw NotApplicable("inelastic: restitution " + g17(scene.walls[w].restitution) + " at walls[" + std::to_string(w) + "]");
  const Run s = run<double>(scene, duration);
  const Run f = run<Fixed>(scene, duration);
  // Which rule acted, by name (the first found), or "".
  auto rule_acted = [](const EngineCounters& c) -> std::string {
    const RestCounters& r = c.rest;
    const std::pair<std::uint64_t, const char*> rules[] = {
        {r.came_to_rest, "came to rest on a face"}, {r.plastic_pairs, "a plastic pair"}, {r.held, "a held contact"},
        {r.fell_asleep, "a ball fell asleep"},      {r.woken, "a ball woken"},          {r.creeping, "creep"},
        {c.ignored, "an ignored contact"}};
    for (const auto& [count, name] : rules)
      if (count > 0) return name;
    return "";
  };
  for (const auto& [run_mode, counters] : {std::pair{"strict", &s.summary.counters}, std::pair{"fixed", &f.summary.counters}})
    if (const std::string rule = rule_acted(*counters); !rule.empty())
      throw NotApplicable(std::string("a rest rule acted (") + rule + ", " + run_mode + "): its outcome is a threshold decision");
  const EngineTrace<double> trace = trace_engine<double>(scene, duration);
  if (auto failure = trace_failure(trace)) return failure;
  const RunScales sc = scales_of(scene, trace);
  const double T = duration;
  const double delta0 = 64 * strict_eps * (sc.position + sc.speed * T + sc.acceleration * T * T);
  const double G = 2 + 4 * sc.speed * T / sc.r_min;
  // Curved surfaces: other balls, and wall ends (a centre beyond the
  // segment's ends, to 1e-9, when it touches).
  std::int64_t curved = 0;
  for (const TracedCollision<double>& c : trace.collisions) {
    if (c.collision.kind == EventKind::ball_ball) {
      ++curved;
      continue;
    }
    const WallSpec& w = scene.walls[c.collision.b];
    const double dx = w.b[0] - w.a[0], dy = w.b[1] - w.a[1];
    const double along = ((c.after_a.position.x - w.a[0]) * dx + (c.after_a.position.y - w.a[1]) * dy) / (dx * dx + dy * dy);
    if (!(along > 1e-9 && along < 1 - 1e-9)) ++curved;
  }
  const double bound = delta0 * static_cast<double>(1 + s.events.size()) * std::pow(G, static_cast<double>(curved));
  // Events must come in the same order, unless the bound has grown to where
  // a near-tie or a near-graze (a gap within the bound) may go either way:
  // then only the positions are compared (and the claim is weak; RC_TAG in
  // scene_properties.cpp would show how often: see docs/PROPERTIES.md).
  bool ties_may_flip = bound > 1e-9 * std::max(sc.position, sc.r_min);
  // Two different events at the same time within what the bound allows (the
  // fastest ball moves `bound` in tie_window) are a tie the runs may break
  // differently, e.g. a ball meeting two coincident walls: from there on only
  // the positions are compared, as above.
  const double tie_window = sc.speed > 0 ? bound / sc.speed : 0;
  const std::size_t n = std::min(s.events.size(), f.events.size());
  for (std::size_t k = 0; k < n && !ties_may_flip; ++k) {
    const EventRecord &x = s.events[k], &y = f.events[k];
    if (x.kind == y.kind && x.a == y.a && x.b == y.b) continue;
    if (std::fabs(x.time - y.time) <= tie_window) {
      ties_may_flip = true;
      break;
    }
    return "event " + std::to_string(k) + ": strict (kind " + std::to_string(x.kind) + ", " + std::to_string(x.a) + ", " +
           std::to_string(x.b) + ", t = " + g17(x.time) + "), fixed (kind " + std::to_string(y.kind) + ", " +
           std::to_string(y.a) + ", " + std::to_string(y.b) + ", t = " + g17(y.time) + "), bound " + g17(bound);
  }
  // Events one run makes beyond the other's, all within tie_window of the
  // run's end, are ties with the end itself (a ball reaching a wall at the
  // last instant: one run's rounding puts it at T, the other's a hair
  // after): the positions decide, as above.
  if (s.events.size() != f.events.size() && !ties_may_flip) {
    const std::vector<EventRecord>& longer = s.events.size() > f.events.size() ? s.events : f.events;
    const bool at_the_end = std::all_of(longer.begin() + static_cast<std::ptrdiff_t>(n), longer.end(),
                                        [&](const EventRecord& e) { return T - e.time <= tie_window; });
    if (!at_the_end)
      return "strict made " + std::to_string(s.events.size()) + " events, fixed " + std::to_string(f.events.size()) +
             " (bound " + g17(bound) + ")";
  }
  const auto& xs = s.frames.back().position;
  const auto& xf = f.frames.back().position;
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (!(std::fabs(xs[k] - xf[k]) <= bound))
      return "final " + std::string(k % 2 ? "y" : "x") + " of ball " + std::to_string(k / 2) + ": strict " + g17(xs[k]) +
             ", fixed " + g17(xf[k]) + ", difference " + g17(std::fabs(xs[k] - xf[k])) + " > bound " + g17(bound) + " (" +
             std::to_string(s.events.size()) + " events, " + std::to_string(curved) + " on curved surfaces)";
  return std::nullopt;
}

}  // namespace

// A gas's three shortcuts against what they stand for, each on its own:
// the gas engine (gas_engine.hpp) against EventEngine (its cell crossings
// only where it ran the whole run: a jam hands the run over to an
// EventEngine that lays its grid out afresh), the plain gas path (EventEngine::collide_in_gas) against the general
// collide() and settle(), and the queue that keeps each ball's earliest
// contact only (event_queue.hpp) against one that keeps every prediction.
// Each must give the same frames and events to the bit, and the same counts
// of everything the engine did (collisions, cell crossings, every rest
// rule), so that the runs made the same predictions as well; stale events
// too for the path, not for the queue, which holds fewer events to go
// stale, nor its creeping contacts (a contact that changes nothing, which
// a queue of every prediction can hold twice, once for each of its balls,
// and judge twice: found by the dense gases, one in 66). Not applicable where a ball accelerates (no gas: neither shortcut
// runs) or where nothing collides.
static CheckResult same_run(const Run& fast, const Run& slow, const char* what, bool same_stale,
                            bool same_crossings = true, bool same_creeping = true) {
  if (const std::string d = frame_difference(fast.frames, 0, slow.frames, 0); !d.empty()) return what + (": " + d);
  if (const std::string d = event_difference(fast.events, 0, slow.events); !d.empty()) return what + (": " + d);
  const EngineCounters &x = fast.summary.counters, &y = slow.summary.counters;
  const std::pair<const char*, std::array<std::uint64_t, 2>> counts[] = {
      {"ball_ball", {x.ball_ball, y.ball_ball}},
      {"ball_wall", {x.ball_wall, y.ball_wall}},
      {"stale", {same_stale ? x.stale : 0, same_stale ? y.stale : 0}},
      {"cell_crossings", {same_crossings ? x.cell_crossings : 0, same_crossings ? y.cell_crossings : 0}},
      {"leave_pair", {x.leave_pair, y.leave_pair}},
      {"leave_wall", {x.leave_wall, y.leave_wall}},
      {"creeping", {same_creeping ? x.rest.creeping : 0, same_creeping ? y.rest.creeping : 0}},
      {"plastic_pairs", {x.rest.plastic_pairs, y.rest.plastic_pairs}},
      {"came_to_rest", {x.rest.came_to_rest, y.rest.came_to_rest}},
      {"held", {x.rest.held, y.rest.held}},
  };
  for (const auto& [name, pair] : counts)
    if (pair[0] != pair[1])
      return std::string(what) + ": " + name + " " + std::to_string(pair[0]) + ", without it " + std::to_string(pair[1]);
  return std::nullopt;
}

// The gas engine (gas_engine.hpp, the default for a gas without fixed
// balls) against EventEngine's plain gas path, that against the general
// path, and against a queue of every prediction.
template <class Num>
CheckResult gas_fast_path_same_bits(const Scene& scene, double duration) {
  if (!no_ball_accelerates(make_world<Num>(scene))) throw NotApplicable("a ball accelerates: not a gas");
  EngineChoice event_engine;
  event_engine.gas_engine = false;
  EngineChoice general = event_engine, every_prediction = event_engine;
  general.plain_gas_path = false;
  every_prediction.earliest_contact_only = false;
  const Run fast = run<Num>(scene, duration, {}, event_engine), slow = run<Num>(scene, duration, {}, general);
  if (slow.events.empty()) throw NotApplicable("nothing collides");
  const Run gas = run<Num>(scene, duration);
  if (auto d = same_run(gas, fast, "gas engine", false, gas.summary.gas_engine_until < 0 || std::isinf(gas.summary.gas_engine_until)))
    return d;
  if (auto d = same_run(fast, slow, "plain gas path", true)) return d;
  return same_run(fast, run<Num>(scene, duration, {}, every_prediction), "earliest contact only", false, true, false);
}

CheckResult check_deterministic(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return deterministic<decltype(zero)>(scene, duration); });
}
CheckResult check_run_file_replay(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return run_file_replay<decltype(zero)>(scene, duration); });
}
CheckResult check_resume_equals_uninterrupted(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return resume_equals_uninterrupted<decltype(zero)>(scene, duration); });
}
CheckResult check_gas_fast_path_same_bits(const Scene& scene, const std::string& mode, double duration) {
  return in_mode(mode, [&](auto zero) { return gas_fast_path_same_bits<decltype(zero)>(scene, duration); });
}
CheckResult check_fixed_matches_strict(const Scene& scene, const std::string&, double duration) {
  try {
    return fixed_matches_strict(scene, duration);
  } catch (const NotApplicable&) {
    throw;  // a discard, not a failure
  } catch (const std::exception& e) {
    return std::string("a run threw: ") + e.what();
  }
}

const std::vector<NamedCheck>& named_checks() {
  static const std::vector<NamedCheck> checks = {
      {"energy-kept", "elastic scenes keep total energy within the derived bound", check_energy_kept},
      {"momentum-kept", "every ball-ball collision of free balls keeps momentum", check_momentum_kept},
      // impulse_checks.cpp
      {"impulses-keep-momentum", "every impulse, whichever rule applied it, keeps momentum but for what supports push",
       check_impulses_keep_momentum},
      {"article-momentum-kept", "the article's two-ball formula keeps momentum (expected to fail)", check_article_momentum_kept},
      {"reflection-speed", "reflections keep tangential speed and scale the normal speed by e", check_reflection_speed},
      {"no-overlap", "no overlap or tunnelling on the continuous motion", check_no_overlap},
      {"deterministic", "the same scene gives the same bits twice", check_deterministic},
      {"run-file-replay", "a run file replays bit for bit", check_run_file_replay},
      {"resume", "resuming from a checkpoint equals the uninterrupted run", check_resume_equals_uninterrupted},
      {"gas-fast-path", "in a gas, the plain gas path and the earliest-contact queue give the bits and counts of what they stand for", check_gas_fast_path_same_bits},
      {"fixed-matches-strict", "fixed and strict agree within the derived bound on short horizons", check_fixed_matches_strict},
      // rest_checks.cpp
      {"energy-never-rises", "energy never rises between frames where every restitution is below 1", check_energy_never_rises},
      {"pile-comes-to-rest", "a pile comes to rest within T_rest from the scene, without overlap", check_pile_comes_to_rest},
      {"wake-keeps-momentum", "a ball dropped on a resting pile wakes it with momentum kept", check_wake_keeps_momentum},
      // bounce_checks.cpp
      {"bounce-comes-to-rest-on-time", "a ball bouncing on a floor comes to rest where the documented rest height says",
       check_bounce_comes_to_rest_on_time},
      {"struck-sleeper-keeps-momentum", "a ball struck while lying on a floor moves, with the pair's horizontal momentum kept",
       check_struck_sleeper_keeps_momentum},
  };
  return checks;
}

const NamedCheck* find_check(const std::string& slug) {
  for (const NamedCheck& c : named_checks())
    if (c.slug == slug) return &c;
  return nullptr;
}

}  // namespace collide2d::properties
