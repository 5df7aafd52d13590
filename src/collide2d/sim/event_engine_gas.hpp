// EventEngine's plain gas path (part of event_engine.hpp, included at its
// end): a strike in a gas, answered without the rest rules' bookkeeping.
#pragma once

#include "collide2d/sim/event_engine.hpp"

namespace collide2d {

// A strike in a gas (no ball accelerates, the analytic method) on balls
// that are moving, in contact with nothing and not struck at this instant
// already: every rest rule is idle there (rest.hpp: no weight to carry, no
// press, no jam), so the response is the textbook one, the islands are the
// struck balls alone, nothing can fall asleep, and collide() and settle()
// would do exactly what collide_in_gas does, with more bookkeeping. The
// same calls in the same order: the same bits (a gas's stored hashes and
// the property gas-fast-path, properties/determinism_checks.cpp,
// holds it to that).
template <class Num, class Observer>
inline bool EventEngine<Num, Observer>::plain_gas_strike(const Event<Num>& e) const {
  if (!plain_gas_path_) return false;
  const Body<Num>& a = world_.balls[e.a];
  if (a.is_static() || graph_.in_contact(e.a) || a.struck_at == e.time) return false;
  if (e.kind != EventKind::ball_ball) return true;
  const Body<Num>& b = world_.balls[e.b];
  return !b.is_static() && !graph_.in_contact(e.b) && !(b.struck_at == e.time);
}

// What plain_gas_strike needs of the run as a whole: a gas, the analytic
// method, and no negative least press (under which a free strike could be
// too slow to part, ContactRules::collide).
template <class Num, class Observer>
inline bool EventEngine<Num, Observer>::plain_gas_scene() const {
  return keeps_predictions_ && method_ == ToiMethod::analytic && !(rules_.thresholds().least_press < Num{});
}

// collide() and settle() for a plain_gas_strike: ball e.a meets its
// partner (n from the partner towards e.a), both carried to now already.
template <class Num, class Observer>
template <class OnCollision>
inline void EventEngine<Num, Observer>::collide_in_gas(const Event<Num>& e, const Vec2<Num>& n,
                                                       OnCollision& on_collision, const Num& until) {
  const bool pair = e.kind == EventKind::ball_ball;
  Body<Num>& a = world_.balls[e.a];
  Body<Num>* b = pair ? &world_.balls[e.b] : nullptr;
  Collision<Num>& c = gas_collision_;
  c.island.assign(1, e.a);
  if (pair) c.island.push_back(e.b);
  for (int x : c.island) advance_to_time(world_.balls[x], now_);  // as collide() carries its island (a no-op but for −0)
  c.island_velocity_before.assign(1, a.velocity);
  if (pair) c.island_velocity_before.push_back(b->velocity);
  const Num restitution = contact_restitution(a.restitution, pair ? b->restitution : world_.wall_restitution[e.b]);
  c.impulse = ContactRules<Num>::textbook_response(a, b, true, pair, n, restitution);
  a.struck_at = e.time;
  if (pair) b->struck_at = e.time;
  c.time = e.time, c.kind = e.kind, c.a = e.a, c.b = e.b;
  for (int x : c.island) motion_changed(x, MotionChange::response);
  on_collision(c);
  // solve_islands: each struck ball is an island of its own, its forces
  // (none, or its own acceleration again after a contact it has left).
  for (int x : c.island) advance_to_time(world_.balls[x], now_);
  graph_.forces(world_, c.island, rules_.thresholds().least_press);
  for (int x : c.island) motion_changed(x, MotionChange::forces);
  // settle: the lower index predicts the pair, the other skips it.
  predict(e.a, until);
  if (pair) predict(e.b, until, [&](int j) { return j == e.a; });
}

}  // namespace collide2d
