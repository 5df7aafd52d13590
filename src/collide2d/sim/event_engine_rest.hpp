// Rest in EventEngine (part of event_engine.hpp, included at its end).
//
// The rules are rest.hpp's and contact_rules.hpp's; this is where the
// engine applies them, through five members:
//  - settle(changed, until), after every event that changed a motion: first
//    wake_uncarried, then the balls of `changed` that can sleep do (rule 2:
//    slower than v_rest and carried, alone or as an island; then
//    wake_uncarried again for the contacts their holds ended), then every
//    ball whose motion changed
//    is predicted again, and the moving neighbours of a new sleeper are
//    predicted against it;
//  - fall_asleep(balls, changed): the balls stop; their moving partners lose
//    their normal speed towards them (ContactRules::hold) and their islands'
//    forces are solved again;
//  - wake(first, changed), for a strike at v_rest or faster on a sleeper
//    (rule 3): it wakes, and so does every sleeper it helped to carry;
//  - wake_uncarried(changed) (rule 3, a support gone): a sleeper whose
//    contact with a moving ball ended in this event is asked again whether
//    its supports carry it, and wakes if not;
//  - moving_partners(i): the moving balls in contact with ball i.
// A ball's motion changes here only through motion_changed, as everywhere
// in the engine: a new version, the observer told.
#pragma once

#include "collide2d/sim/event_engine.hpp"

namespace collide2d {

// The moving balls in contact with ball i.
template <class Num, class Observer>
inline std::vector<int> EventEngine<Num, Observer>::moving_partners(int i) const {
  std::vector<int> out;
  graph_.for_each_contact_of(i, [&](const PersistentContact<Num>& c) {
    const int p = c.partner_of(i);
    if (p >= 0 && !world_.balls[p].is_static()) out.push_back(p);
  });
  return out;
}

// After a contact: balls that can sleep do (in index order, again while
// one more falls asleep: a ball may be carried by one that just slept),
// then every ball whose motion changed is predicted again, and every moving
// neighbour of a ball that fell asleep is predicted against it.
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::settle(std::vector<int>& changed, const Num& until) {
  auto tidy = [](std::vector<int>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  tidy(changed);
  wake_uncarried(changed);
  tidy(changed);
  std::vector<int> slept;
  // A ball of an island already found unable to sleep, since the last ball
  // fell asleep, has that island and that answer (the tests change
  // nothing): judged_[x] == judgement_ marks it, and a sleep starts a new
  // judgement. A strike on a pile changes every ball of its island; each
  // would otherwise search the whole island again.
  if (judged_.size() != world_.balls.size()) judged_.assign(world_.balls.size(), 0);
  for (bool more = true; more;) {
    more = false;
    ++judgement_;
    std::vector<int> more_changed;
    for (int i : changed) {
      if (world_.balls[i].is_static()) continue;
      if (rules_.can_sleep(world_, grid_, graph_, i)) {
        fall_asleep({i}, more_changed);
        slept.push_back(i);
        more = true;
        ++judgement_;
      } else if (graph_.in_contact(i) && judged_[i] != judgement_) {
        const std::vector<int> island = graph_.island(world_, {i});
        if (rules_.island_can_sleep(world_, island)) {
          fall_asleep(island, more_changed);
          slept.insert(slept.end(), island.begin(), island.end());
          more = true;
          ++judgement_;
        } else {
          for (int x : island) judged_[x] = judgement_;
        }
      }
    }
    changed.insert(changed.end(), more_changed.begin(), more_changed.end());
    tidy(changed);
  }
  // Contacts that the holds and forces of the balls that fell asleep just
  // now ended: their other sleepers are asked as well, once (the new
  // sleepers themselves are not: their own holds ended those contacts).
  if (!slept.empty() && !graph_.parted().empty()) {
    std::vector<int> now_asleep = slept;
    std::sort(now_asleep.begin(), now_asleep.end());
    std::erase_if(graph_.parted(), [&](int x) { return std::binary_search(now_asleep.begin(), now_asleep.end(), x); });
    wake_uncarried(changed);
    tidy(changed);
  }
  auto in_changed = [&](int j) { return std::binary_search(changed.begin(), changed.end(), j); };
  for (int i : changed) {
    if (world_.balls[i].is_static()) continue;
    predict(i, until, [&](int j) { return j < i && in_changed(j) && !world_.balls[j].is_static(); });
  }
  for (int s : slept)
    grid_.for_each_neighbour(s, [&](int j) {
      if (!in_changed(j) && !world_.balls[j].is_static()) predict_pair(j, s, until);
    });
}

// Rule 3, a support gone. A sleeper is carried under its load: its weight
// plus the pushes of the moving balls it touches (ContactRules::carried).
// Where a contact between it and a moving ball ended during this event,
// before its settling (the contact left the graph: ContactGraph::parted),
// the push is gone: the sleeper is asked again, in index order, and wakes
// if its supports no longer carry it. Otherwise a ball pushed into a corner by another that
// then rolls away stays there, held by nothing (the shrunk pile of
// pile-comes-to-rest, seed 7165064745050203442: a ball asleep against a
// wall on a floor that slopes away from it). Only an ended contact asks: a
// push that merely changed, or a new contact, does not (asking then too
// woke a ball put to sleep on a push at the very instant its partner
// struck it again, for ever: the unseen pile_30_e060 stalled at t = 2.41).
// The balls woken take their islands' forces. Settle asks twice: as it
// begins, and once more for the contacts its own sleepers' holds and
// forces ended.
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::wake_uncarried(std::vector<int>& changed) {
  std::vector<int>& asked = graph_.parted();
  std::erase_if(asked, [&](int x) { return !world_.balls[x].asleep; });
  if (asked.empty()) return;
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  // Waking removes no contact, so `asked` stays as it is through the loop;
  // it is emptied before the islands' solves, whose partings are the next
  // pass's.
  const std::size_t before = changed.size();
  for (int s : asked)
    if (world_.balls[s].asleep && !rules_.carried(world_, grid_, graph_, s)) wake(s, changed);
  asked.clear();
  if (changed.size() == before) return;
  const std::vector<int> woken(changed.begin() + static_cast<std::ptrdiff_t>(before), changed.end());
  solve_islands(woken, changed);
}

// Rule 2: `balls` fall asleep. Their contacts stay; their moving partners
// now lean on static balls, and lose what normal speed they had relative
// to them (an impact of their islands with every contact held: less than
// v_rest each); those islands' forces are solved again.
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::fall_asleep(const std::vector<int>& balls, std::vector<int>& changed) {
  for (int i : balls) {
    advance_to_time(world_.balls[i], now_);
    rules_.put_to_sleep(world_.balls[i]);
    graph_.mobility_changed(i);
    motion_changed(i, MotionChange::sleep);
  }
  std::vector<int> partners;
  for (int i : balls)
    for (int p : moving_partners(i)) partners.push_back(p);
  if (partners.empty()) return;
  const std::vector<int> island = graph_.island(world_, partners);
  for (int x : island) advance_to_time(world_.balls[x], now_);
  rules_.hold(world_, graph_, island);
  solve_islands(partners, changed);
}

// Rule 3: ball i wakes; so does every sleeper it helped to carry: within
// the contact band of it, and no longer carried (the cone test again, now
// without it). Each ball woken joins `changed`, and so do the moving balls
// in contact with it (their partner moves now). The set that wakes does
// not depend on the order of the search (waking only ever removes
// supports), nor on the grid (only balls within the band are asked).
template <class Num, class Observer>
inline void EventEngine<Num, Observer>::wake(int first, std::vector<int>& changed) {
  std::vector<int> pending = {first};
  while (!pending.empty()) {
    const int i = pending.back();
    pending.pop_back();
    Body<Num>& b = world_.balls[i];
    if (!b.asleep) continue;
    advance_to_time(b, now_);
    ContactRules<Num>::wake(b);
    graph_.mobility_changed(i);
    motion_changed(i, MotionChange::wake);
    ++rules_.counters.woken;
    changed.push_back(i);
    for (int p : moving_partners(i)) changed.push_back(p);
    grid_.for_each_neighbour(i, [&](int j) {
      if (j != i && world_.balls[j].asleep && rules_.within_band(world_.balls[j], b) &&
          !rules_.carried(world_, grid_, graph_, j))
        pending.push_back(j);
    });
  }
}

}  // namespace collide2d
