// EventEngine's predictions (part of event_engine.hpp, included at its end):
// when each moving ball's next events come. A pair is predicted from the
// later of its two clocks and a wall from the ball's own, so that an answer
// depends only on the motions, never on when or whether the grid asks for
// it: the grid changes the cost of a run, never its bits. What is found is
// pushed into the queue (event_queue.hpp) with the versions it was
// predicted from; a later change of either ball's motion makes it stale.
#pragma once

#include <cmath>

#include "collide2d/sim/event_engine.hpp"

namespace collide2d {

// `owner`: the moving ball whose prediction this is (its place in the queue).
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::push(Event<Num> e, int owner) {
  if (contacts_after_ && is_contact(e.kind)) {
    const bool earlier = after_in_order(*contacts_after_, e);
    const bool same_place = !earlier && !after_in_order(e, *contacts_after_);
    if (earlier || (same_place && !contacts_from_stale_)) return;
  }
  const std::uint64_t owner_version = world_.balls[owner].version;
  if (!queue_.would_keep(e, owner, owner_version)) return;
  e.version_a = world_.balls[e.a].version;
  if (between_two_balls(e.kind)) e.version_b = world_.balls[e.b].version;
  queue_.push(e, owner, owner_version);
}

// Every future event of moving ball i within [now, until]: against its
// neighbours but those `skip(j)` names (pairs predicted elsewhere) and
// those it is in contact with, the walls near its cell, the end of each of
// its contacts, and leaving its cell.
template <class Num, class Observer>
template <class Skip>
inline void EventEngine<Num, Observer>::predict(int i, const Num& until, Skip skip) {
  const Body<Num>& bi = world_.balls[i];
  if (bi.is_static()) return;
  for (int j : neighbours_of(i, skip)) predict_pair(i, j, until);
  const Num horizon = until - now_;
  const BallState<Num> si = state_at(bi, now_);
  for (int w : grid_.walls_near(i)) predict_wall(i, w, until);
  graph_.for_each_contact_of(i, [&](const PersistentContact<Num>& c) {
    const int partner = c.partner_of(i);
    if (i == c.i || partner < 0 || world_.balls[partner].is_static()) predict_contact_ending(c, horizon, i);
  });
  predict_crossing(i, si, horizon);
}

// The next contact of moving ball i with wall w, predicted from the ball's
// clock (the last change of its motion), so that a wall first met at a
// cell crossing gives the same answer as at that change. In contact with a
// wall's face, the ball cannot meet its ends; on the tangent at an end its
// centre stays outside that end's circle, and cannot reach the face: a
// contact with the feature it touches, or with the face from an end, is a
// rounding echo. At a crossing (`now_` past the clock) an answer before now
// is one the ball had from an earlier cell near the wall too, and handled.
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::predict_wall(int i, int w, const Num& until) {
  const Body<Num>& bi = world_.balls[i];
  const PersistentContact<Num>* touching = graph_.with_wall(i, w);
  if (touching && touching->feature == ContactFeature::wall_face) return;
  const ContactFeature resting_on = touching ? touching->feature : ContactFeature::none;
  const BallState<Num> si = state_at(bi, bi.time);
  const Num horizon = until - bi.time;
  if constexpr (requires(Observer& o) { o.ball_wall_asked(si, w, horizon); }) observer_.ball_wall_asked(si, w, horizon);
  const ToiResult<Num> r = wall_contact(si, w, horizon);
  if (r.hit() && !(touching && (r.feature == resting_on || r.feature == ContactFeature::wall_face)) &&
      !(bi.time + r.time < now_))
    push({bi.time + r.time, EventKind::ball_wall, i, w, r.feature}, i);
  // A ball a hair inside the wall by rounding and pressed into it meets it
  // now, whatever later event the time of impact may also find with this
  // wall (an end beside the ball): the earlier event is taken, and the
  // other is stale once the ball's motion changes.
  if (method_ == ToiMethod::analytic && !(r.hit() && r.time == Num{}))
    predict_pressed_on_wall(i, si, w, horizon, resting_on);
}

template <class Num, class Observer>
inline void EventEngine<Num, Observer>::predict(int i, const Num& until) {
  predict(i, until, [](int) { return false; });
}

// Ball i's neighbours but those `skip(j)` names. They are gathered first
// and their bodies asked for from memory all at once: in a large gas each
// is a cache miss, and the misses then overlap instead of coming one
// after another.
template <class Num, class Observer>
template <class Skip>
inline const std::vector<int>& EventEngine<Num, Observer>::neighbours_of(int i, Skip skip) {
  std::vector<int>& near = neighbours_;
  near.clear();
  grid_.for_each_neighbour(i, [&](int j) {
    if (j == i || skip(j)) return;
    near.push_back(j);
    prefetch_object(&world_.balls[j]);
  });
  return near;
}

// Moving ball i's kept contact `e` came out of the queue and left i's
// motion as it was (event_queue.hpp): its next contact from e on, against
// every neighbour and wall near. The contacts it had predicted come out
// the same, to the bit, for they depend on the clocks alone; a contact
// with a partner that has changed since is also that partner's
// prediction, and held there. After e itself (processed, and changing
// nothing: asked again, it would come back), or, if e was `stale`, from
// e's place in the order on: the queue kept e over a copy equal in (time,
// kind, a, b) but predicted from the partner's new motion, pushed later.
template <class Num, class Observer>
inline void
EventEngine<Num, Observer>::predict_contacts_after(int i, const Event<Num>& e, const Num& until, bool stale) {
  if (world_.balls[i].is_static()) return;
  contacts_after_ = &e;
  contacts_from_stale_ = stale;
  for (int j : neighbours_of(i, [](int) { return false; })) predict_pair(i, j, until);
  for (int w : grid_.walls_near(i)) predict_wall(i, w, until);
  contacts_after_ = nullptr;
}

// The next contact of balls i (moving) and j, predicted from the later of
// their clocks (the last change of either's motion): the answer depends
// only on the two motions, never on when, or whether, the grid asks for it.
// None for two balls in contact (the end of their contact is the event).
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::predict_pair(int i, int j, const Num& until) {
  const Body<Num>& bi = world_.balls[i];
  const Body<Num>& bj = world_.balls[j];
  if (bi.is_static() && bj.is_static()) return;
  if (graph_.touching(i, j)) return;
  if constexpr (!requires(Observer& o, const BallState<Num>& s, const Num& h) { o.ball_ball_asked(s, s, h); })
    if (certainly_apart_until(bi, bj, until)) return;
  // The clock first: the neighbour's flags are on its second cache line.
  const Num t0 = bj.time < bi.time || bj.fixed ? bi.time : bj.time;
  const BallState<Num> si = state_at(bi, t0), sj = state_at(bj, t0);
  const Num horizon = until - t0;
  if constexpr (requires(Observer& o) { o.ball_ball_asked(si, sj, horizon); }) observer_.ball_ball_asked(si, sj, horizon);
  const RootSearch<Num> r = method_ == ToiMethod::analytic ? time_of_contact_ball_ball(si, sj, horizon)
                                                           : bisection_contact(si, sj, horizon);
  if (r.found) {
    push({t0 + r.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), ContactFeature::ball}, i);
    return;
  }
  // Nothing presses two balls of the same acceleration together (Δp·Δa =
  // 0, never below −least_press ≤ 0): no pressed contact, and a gas skips
  // forming its arguments.
  if (si.acceleration == sj.acceleration) return;
  const Vec2<Num> dp = si.position - sj.position, dv = si.velocity - sj.velocity, da = si.acceleration - sj.acceleration;
  const Num R = si.radius + sj.radius;
  const RootSearch<Num> pressed =
      pressed_contact_due(dp, dv, da, R, largest_magnitude(si.position) + largest_magnitude(sj.position) + R, horizon,
                          [&](const Num& t) { return within_reach(position_at(dp, dv, da, t), R); });
  if (pressed.found)
    push({t0 + pressed.t, EventKind::ball_ball, std::min(i, j), std::max(i, j), ContactFeature::ball}, i);
}

// True when balls i and j cannot come within R + h_rest of each other
// before `until`, so that neither a time of impact nor a pressed contact
// (which needs them within R + h_rest) can be found for them. Each ball
// moves from its own clock by at most D = |v|₁ H + ½ |a|₁ H² (H = until −
// its clock), so their centres stay at least |p_i − p_j| − D_i − D_j apart
// (the positions each at its ball's clock). A screen in doubles, widened
// by 2^-28 of the reach and 2^-40 of the coordinates for the rounding of
// the motions and of the screen itself: it decides only which pairs are
// searched, never an answer. It spares the states, the relative motion
// and the trajectory box of most of a pile's neighbours after a strike
// (pile_120_e050 to t = 3: 46.7 M pairs asked for 113 k events, 93 % of
// them cleared by the box).
template <class Num, class Observer>
inline bool EventEngine<Num, Observer>::certainly_apart_until(const Body<Num>& bi, const Body<Num>& bj,
                                                             const Num& until) const {
  auto d = [](const Num& x) { return screen_value(x); };
  const double end = d(until);
  auto moves = [&](const Body<Num>& b) {
    const double H = end - d(b.time);
    const double v = std::fabs(d(b.velocity.x)) + std::fabs(d(b.velocity.y));
    const double a = std::fabs(d(b.acceleration.x)) + std::fabs(d(b.acceleration.y));
    return H * (v + 0.5 * a * H);
  };
  const double xi = d(bi.position.x), yi = d(bi.position.y), xj = d(bj.position.x), yj = d(bj.position.y);
  const double dx = xi - xj, dy = yi - yj;
  const double coordinates = std::fabs(xi) + std::fabs(yi) + std::fabs(xj) + std::fabs(yj);
  const double reach = (d(bi.radius) + d(bj.radius) + d(rules_.thresholds().height) + moves(bi) + moves(bj)) * (1 + 0x1p-28) +
                       0x1p-40 * coordinates;
  return reach * reach < dx * dx + dy * dy;
}

// An offset of at most R + h_rest between centres (or from a wall's nearest point).
template <class Num, class Observer>
inline bool EventEngine<Num, Observer>::within_reach(const Vec2<Num>& offset, const Num& R) const {
  const Num reach = R + rules_.thresholds().height;
  return !(reach * reach < length_squared(offset));
}

// Pressed together while touching. Rounding can leave a pair (Δp the
// offset between centres, or from a wall's nearest point; R the contact
// distance) a hair inside contact, where the gap never crosses zero again
// and no time of impact exists; the contact is then due when their normal
// separating speed has fallen to zero: t = (Δp·Δv) / −(Δp·Δa) for
// Δp·Δv ≥ 0, at once otherwise. Only while the rise before that,
// s_n² / 2|a_n| = (Δp·Δv)² / (2 |Δp·Δa| |Δp|), stays within h_rest
// (|Δp| ≈ R): a larger rise would take them apart, and the time of impact
// would have seen them come back. Motion along the tangent of a round
// partner (another ball, a wall's end) carries them apart as well, which
// the normal speed does not see: the contact is due only if at that time
// the caller's `still_touching(t)` holds, the pair within h_rest of
// touching (a ball hopping straight up from a wall's end it was pressed
// against sideways is not on it at the top of its hop).
//
// Rounding is measured against `scale`, the largest coordinate the offset
// was formed from: a double rounds positions to 2^-53 of their magnitude,
// so far from the origin (2^26, with balls of radius 2^-10) a ball left on
// a wall after a bounce can be inside it by 1e-8, more than its next hop
// rises (a hop of 3e-9 never brings the gap back above zero, and the time
// of impact finds no root). Touching therefore counts to within ρ = 2^-50
// of the scale (the offset's few roundings, 2^-53 of it each), and the
// rise that keeps the contact is h_rest plus the depth it starts at: a
// rise that cannot clear the contact is no flight. (A margin of ρ on the
// rise as well made hops of a quarter radius contacts in a scene at 2^29
// with balls of radius 2^-18, and stalled it.)
template <class Num, class Observer>
template <class StillTouching>
inline RootSearch<Num>
EventEngine<Num, Observer>::pressed_contact_due(const Vec2<Num>& dp, const Vec2<Num>& dv, const Vec2<Num>& da,
                                                const Num& R, const Num& scale, const Num& horizon,
                                                StillTouching still_touching) const {
  const Num zero{};
  const Num pressing = dot(dp, da);
  // Not pressed together (most pairs a prediction asks): nothing more to form.
  if (!(pressing < -rules_.thresholds().least_press)) return {};
  // Touching to rounding counts: the time of impact finds no root for a
  // gap of a few ulps of R either (its band test and this one round apart).
  const Num rounding = num<Num>(0x1p-50) * scale;
  const Num R2 = R * R, reach_relative = R2 + R2 * num<Num>(0x1p-40), reach_absolute = (R + rounding) * (R + rounding);
  const Num reach_squared = reach_relative < reach_absolute ? reach_absolute : reach_relative;
  const Num offset_squared = length_squared(dp);
  if (reach_squared < offset_squared) return {};
  const Num separating = dot(dp, dv);
  // rise = s² / (2 |p| R) with s = Δp·Δv, p = Δp·Δa; depth ≈ (R² − |Δp|²) / 2R.
  // The depth is not bounded by the rounding: a ball that cannot rise out
  // of an overlap of any depth has no time of impact either, and would
  // sink on without this contact.
  const Num depth_term = offset_squared < R2 ? -pressing * (R2 - offset_squared) : zero;
  const Num keeps_contact = num<Num>(2.0) * -pressing * R * rules_.thresholds().height + depth_term;
  if (keeps_contact < separating * separating) return {};
  if (horizon * -pressing < separating) return {};  // not within the horizon (and no division that could overflow)
  const Num due = separating < zero ? zero : separating / -pressing;
  if (zero < due && !still_touching(due)) return {};
  return {true, due};
}

// The wall's counterpart of a pair left a hair inside contact (see
// pressed_contact_due): the ball touches the wall's nearest point q, is
// pressed towards it (Δp·a < 0 with Δp = p − q) and no time of impact
// exists. The contact is due when it stops moving away from q.
// `resting_on`: the end of this wall the ball is in contact with (its
// centre stays outside that end's circle: an echo, not a contact).
template <class Num, class Observer>
inline void
EventEngine<Num, Observer>::predict_pressed_on_wall(int i, const BallState<Num>& s, int w, const Num& horizon,
                                                    ContactFeature resting_on) {
  if (s.acceleration == Vec2<Num>{}) return;  // nothing presses it on the wall (as for a pair, above)
  ContactFeature feature = ContactFeature::none;
  const Vec2<Num> q = nearest_point(world_.walls[w], s.position, &feature);
  if (feature == resting_on) return;
  // Still touching: within h_rest of the wall (its face or either end,
  // whichever is nearest then), wherever along it the ball has moved.
  auto still_touching = [&](const Num& t) {
    if (feature == ContactFeature::wall_face) return true;
    const Vec2<Num> p = position_at(s, t);
    return within_reach(p - nearest_point(world_.walls[w], p), s.radius);
  };
  const RootSearch<Num> pressed =
      pressed_contact_due(s.position - q, s.velocity, s.acceleration, s.radius,
                          largest_magnitude(s.position) + largest_magnitude(q) + s.radius, horizon, still_touching);
  const Num due = world_.balls[i].time + pressed.t;
  if (pressed.found && !(due < now_)) push({due, EventKind::ball_wall, i, w, feature}, i);
}

template <class Num, class Observer>
inline void EventEngine<Num, Observer>::predict_crossing(int i, const BallState<Num>& s, const Num& horizon) {
  const typename CellGrid<Num>::Crossing c = grid_.next_crossing(i, s, horizon, now_);
  if (c.found) push({now_ + c.time, EventKind::cell_crossing, i, static_cast<int>(c.step), ContactFeature::none}, i);
}

template <class Num, class Observer>
inline RootSearch<Num>
EventEngine<Num, Observer>::bisection_contact(const BallState<Num>& si, const BallState<Num>& sj,
                                              const Num& horizon) const {
  const ToiResult<Num> r = bisection_ball_ball(si, sj, horizon, eps_);
  return {r.hit(), r.time};
}

template <class Num, class Observer>
inline ToiResult<Num>
EventEngine<Num, Observer>::wall_contact(const BallState<Num>& s, int w, const Num& horizon) const {
  switch (method_) {
    case ToiMethod::analytic: return time_of_impact_ball_wall(s, world_.walls[w], horizon);
    case ToiMethod::bisection: return bisection_ball_wall(s, world_.walls[w].segment, horizon, eps_);
    case ToiMethod::seed: return seed_ball_wall(s, world_.walls[w].segment, horizon);
  }
  return {};
}

// When a point moving as p + v t + ½ a t² along the unit tangent t first
// leaves lo < t·(p − origin) < hi: along(t) = C + 2 b t + A t² falls
// through lo, or rises through hi.
template <class Num, class Observer>
inline RootSearch<Num>
EventEngine<Num, Observer>::first_exit(const Vec2<Num>& tangent, const Vec2<Num>& p, const Vec2<Num>& v,
                                       const Vec2<Num>& a, const Vec2<Num>& origin, const Num& lo, const Num& hi,
                                       const Num& horizon) const {
  using T = NumberTraits<Num>;
  auto first_root = [&](Num A, Num b, Num C) {
    normalise_quadratic(A, b, C);
    return first_downward_root(A, b, C, [&] { return compensated_discriminant(A, b, C); }, horizon);
  };
  const Num A = T::half(dot(tangent, a)), b = T::half(dot(tangent, v));
  const Num C = dot(tangent, p - origin);
  const RootSearch<Num> past_lo = first_root(A, b, C - lo);
  const RootSearch<Num> past_hi = first_root(-A, -b, hi - C);
  RootSearch<Num> first = past_lo;
  if (past_hi.found && (!first.found || past_hi.t < first.t)) first = past_hi;
  return first;
}

// A persistent contact (contact_graph.hpp) ends when its offset (p_i − p_j,
// or p_i against a wall) has slid out of (lo, hi) along its tangent.
template <class Num, class Observer>
inline void
EventEngine<Num, Observer>::predict_contact_ending(const PersistentContact<Num>& c, const Num& horizon, int owner) {
  const BallState<Num> si = state_at(world_.balls[c.i], now_);
  Vec2<Num> p = si.position, v = si.velocity, a = si.acceleration;
  if (!c.with_wall()) {
    const BallState<Num> sj = state_at(world_.balls[c.j], now_);
    p = p - sj.position, v = v - sj.velocity, a = a - sj.acceleration;
  }
  // Past an end of its range already (two contacts made at one instant,
  // with one range, reach its end at one instant too: the first to be
  // processed re-predicts the other from there, a rounding past it), it
  // ends now; first_exit looks only ahead.
  const Vec2<Num> tangent = tangent_of(c.normal);
  const Num along = dot(tangent, p - c.origin);
  RootSearch<Num> r;
  if (along < c.lo || c.hi < along) r.found = true, r.t = Num{};
  else r = first_exit(tangent, p, v, a, c.origin, c.lo, c.hi, horizon);
  if (!r.found) return;
  if (c.with_wall()) push({now_ + r.t, EventKind::leave_wall, c.i, c.wall, c.feature}, owner);
  else push({now_ + r.t, EventKind::leave_pair, c.i, c.j, ContactFeature::ball}, owner);
}

}  // namespace collide2d
