// Persistent contacts: the graph of what touches what (rest.hpp, rules 1 and
// 4), its impacts and its constant contact forces.
//
// A contact c holds ball i against a partner: another ball j, or a wall
// (its face, or one of its round ends). With n_c its unit normal (from the
// partner towards i), the relative normal velocity n_c·(v_i − v_j) and
// acceleration are held at zero while the offset (p_i − p_j, or p_i against
// a wall) slides along the tangent within (lo, hi): the wall's ends for a
// face, ±L = ±sqrt(2 R h_rest + h_rest²) about where it began for a round
// partner (there it has risen h_rest off the curve: rest.hpp).
//
// Each moving ball x answers a force f with the acceleration f / m_x; a
// static ball (fixed, asleep) and a wall do not move. The moving balls
// connected through contacts form an island (a static partner ends the
// island there: it carries, it does not pass on). For an island, with
// A_cd = Σ_{x ∈ c∩d, moving} (n_c^x · n_d^x) / m_x (n_c^x: n_c pointing
// towards x), the contact forces λ solve the linear complementarity problem
//     w = A λ + b ≥ 0,  λ ≥ 0,  λ·w = 0,   b_c = Σ_{x ∈ c} n_c^x · g_x,
// g_x the ball's own acceleration: each contact pushes, or lets go (w > 0)
// and leaves; never pulls, never sinks. An impact is the same problem with
// velocities (b_c the relative normal velocity, λ the impulses), and the
// struck contact, if any, held to the equation w = −e v_n (restitution e)
// instead: the whole island answers the strike at once, so a ball resting
// on a wall and struck into it moves along the wall at once rather than
// ringing between the wall and the striker at one instant. Kinetic energy
// cannot rise (rounding aside): Δ KE = Σ_c P_c (v_c + v_c') / 2, where every
// held contact has v_c ≈ 0 before and v_c' = 0 or P_c = 0 after, and the
// struck one v_c' = −e v_c with e ≤ 1.
//
// Contacts and rows are kept in (i, j, wall) order, so the answers do not
// depend on the order in which contacts were made.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "collide2d/sim/lcp.hpp"
#include "collide2d/sim/state_bytes.hpp"
#include "collide2d/sim/world.hpp"

namespace collide2d {

template <class Num>
struct PersistentContact {
  int i = 0;                                     // a ball
  int j = -1;                                    // the partner ball (i < j), or −1 for a wall
  int wall = -1;                                 // the partner wall, or −1
  ContactFeature feature = ContactFeature::ball;  // ball, wall_face, wall_end_a or wall_end_b
  Vec2<Num> normal;                              // unit, from the partner towards i
  Vec2<Num> origin;                              // the offset when it began
  Num lo{}, hi{};                                // it ends when tangent·(offset − origin) leaves (lo, hi)
  Num force{};                                   // λ from the last solve of its island's forces

  bool with_wall() const { return j < 0; }
  int partner_of(int a) const { return a == i ? j : i; }
  auto key() const { return std::tuple(i, j, wall); }
};

// What the island solves cost, for the run summary: the LCPs of strikes
// and plastic impacts (with their re-solves, rule 1's slow partings held)
// and of contact forces; their rows and their pivoting rounds (one
// elimination of the active rows each, lcp.hpp), and the largest island.
struct IslandSolveCounters {
  std::uint64_t impact_solves = 0, force_solves = 0, rows = 0, rounds = 0, largest = 0;
};

template <class Num>
class ContactGraph {
 public:
  IslandSolveCounters solve_counters;

  void reset(std::size_t balls) {
    contacts_.clear();
    parted_.clear();
    of_ball_.assign(balls, {});
    listed_.clear();
    indexed_.clear();
    changed_.assign(balls, 1);
  }
  const std::vector<PersistentContact<Num>>& contacts() const { return contacts_; }

  bool touching(int a, int b) const { return find_pair(a, b) != nullptr; }
  const PersistentContact<Num>* find_pair(int a, int b) const {
    for (int c : listed(a))
      if (!contacts_[c].with_wall() && contacts_[c].partner_of(a) == b) return &contacts_[c];
    return nullptr;
  }
  const PersistentContact<Num>* with_wall(int a, int w) const {
    for (int c : listed(a))
      if (contacts_[c].wall == w) return &contacts_[c];
    return nullptr;
  }
  bool in_contact(int a) const { return of_ball_[static_cast<std::size_t>(a)].count != 0; }

  template <class Visit>
  void for_each_contact_of(int a, Visit visit) const {
    for (int c : listed(a)) visit(contacts_[c]);
  }

  void add(const PersistentContact<Num>& c) {
    contacts_.insert(first_not_before(c), c);
    mark(c);
    reindex();
  }
  // Contact `moved` (already in the graph, found by its key) takes the
  // normal, origin and range given; its balls' forces are to be found again.
  void reshape(const PersistentContact<Num>& moved) {
    const auto at = first_not_before(moved);
    if (at == contacts_.end() || at->key() != moved.key()) return;
    at->normal = moved.normal;
    at->origin = moved.origin;
    at->lo = moved.lo;
    at->hi = moved.hi;
    mark(moved);
  }
  void remove(const PersistentContact<Num>& gone) {
    erase(gone);
    reindex();
  }
  // A trial impact that may be taken back (ContactRules::collide: a strike
  // answered with its restitution, then made plastic where the rebound is
  // too low) keeps the contacts it removes; taking it back puts them in
  // again, so that the plastic impact starts from the contacts the strike
  // found, as the velocities it starts from are the strike's.
  void keep_removed() { removed_.clear(), keeping_removed_ = true; }
  void forget_removed() { removed_.clear(), keeping_removed_ = false; }
  // (Not `except`: the caller adds it anew.)
  void restore_removed(const PersistentContact<Num>& except) {
    keeping_removed_ = false;
    for (const PersistentContact<Num>& c : removed_)
      if (const auto at = first_not_before(c); c.key() != except.key() && (at == contacts_.end() || at->key() != c.key())) {
        contacts_.insert(at, c);
        mark(c);
      }
    if (!removed_.empty()) reindex();
    removed_.clear();
  }

  // The balls of every contact removed since they were last taken (in the
  // order they left, with repeats): a sleeper among them may have lost a
  // push that helped to carry it (rest.hpp, rule 3). The engine clears them
  // as an event begins and takes them as its settling begins
  // (EventEngine::wake_uncarried).
  std::vector<int>& parted() { return parted_; }
  // Ball x fell asleep or woke: the forces of its island and of its
  // partners' islands are to be found again.
  void mobility_changed(int x) {
    changed_[x] = 1;
    for (int c : listed(x)) mark(contacts_[c]);
  }

  // The moving balls connected to the moving ones of `seeds` through contacts
  // between moving balls, sorted.
  // Seeds without contacts (a gas: every collision) are their own islands,
  // found without a search; a search marks what it has seen with a stamp of
  // its own, so that no call costs work in proportion to all the balls.
  std::vector<int> island(const World<Num>& world, const std::vector<int>& seeds) const {
    std::vector<int> out;
    island(world, seeds, out);
    return out;
  }
  // The same into `out`, whose storage is reused (an event in a gas
  // allocates nothing).
  void island(const World<Num>& world, std::span<const int> seeds, std::vector<int>& out) const {
    out.clear();
    for (int s : seeds)
      if (!world.balls[s].is_static()) out.push_back(s);
    if (std::none_of(out.begin(), out.end(), [&](int x) { return in_contact(x); })) {
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
      return;
    }
    std::vector<int>& stack = stack_;
    stack.swap(out);
    out.clear();
    if (seen_.size() != of_ball_.size()) seen_.assign(of_ball_.size(), 0);
    if (++stamp_ == 0) {  // the stamps wrapped: start them again
      std::fill(seen_.begin(), seen_.end(), 0);
      stamp_ = 1;
    }
    while (!stack.empty()) {
      const int x = stack.back();
      stack.pop_back();
      if (seen_[x] == stamp_) continue;
      seen_[x] = stamp_;
      out.push_back(x);
      for (int c : listed(x)) {
        const int y = contacts_[c].partner_of(x);
        if (y >= 0 && !world.balls[y].is_static()) stack.push_back(y);
      }
    }
    // Sorted: an island of more than an eighth of the balls (a pile's)
    // is read off the stamps in index order, cheaper than sorting it.
    if (out.size() * 8 < seen_.size()) return std::sort(out.begin(), out.end());
    out.clear();
    for (std::size_t x = 0; x < seen_.size(); ++x)
      if (seen_[x] == stamp_) out.push_back(static_cast<int>(x));
  }

  // The island `balls` (carried to the present by the caller) takes the
  // impulses of an impact (see the top). `strike`, if given, is the contact
  // being struck, answered with restitution e (in the graph already, or not).
  // Held contacts that part leave, unless they part slower than
  // `rest_speed` (a rise too low to count, rest.hpp): those are held at zero
  // whatever the sign of their impulse, as in the old held face, so that
  // rounding in a strike cannot lift a ball a hair off its wall and loop.
  // Returns the impulse on the strike.
  // If the strike was answered along the free part of its direction (see
  // strike_along_free_part), `free_part` receives that direction, d̂ per ball.
  // Without a strike, every contact closing takes a plastic impact; the
  // impulse on `reported` (a contact of the graph), if given, is returned.
  Num impact(World<Num>& world, const std::vector<int>& balls, const PersistentContact<Num>* strike, const Num& e,
             const Num& rest_speed, std::vector<std::pair<int, Vec2<Num>>>* free_part = nullptr,
             const PersistentContact<Num>* reported = nullptr) {
    auto velocity = [&](int x) { return world.balls[x].is_static() ? Vec2<Num>{} : world.balls[x].velocity; };
    const Num target = strike ? -(e * relative_normal(*strike, velocity)) : Num{};  // v_n' = −e v_n
    const Solution s = solve_island(world, balls, strike, velocity, target, e, &rest_speed);
    apply_impulses(world, s);
    leave(s, strike != nullptr);
    if (!strike) {
      for (std::size_t r = 0; reported && r < s.rows.size(); ++r)
        if (s.rows[r].key() == reported->key()) return s.x[r];
      return Num{};
    }
    if (!s.kick.empty()) {  // answered in velocities, nothing to refine
      // The kick keeps the held contacts' normal speeds (J_H M⁻¹ d = 0),
      // which is right only where they are zero: a contact just turned onto
      // the line of centres (ContactRules::align_round_contacts) has the
      // tangential speed times the angle it turned by. A plastic impact of
      // the held contacts takes that away, as the impact below would (a
      // ball pinched between two balls and left creeping towards the upper
      // one at that speed struck it every 6.3e-10 s, for ever).
      const Solution held = solve_island(world, balls, nullptr, velocity, Num{}, Num{}, &rest_speed);
      apply_impulses(world, held);
      leave(held, false);
      if (free_part) *free_part = s.free_part;
      return s.strike_impulse;
    }
    // A strike nearly along a held contact (a wedge whose two normals are
    // parallel to rounding, ε apart) takes impulses of order v/ε whose sum
    // cancels to v: the contacts are left off their targets by about
    // ε_mach v/ε, which would carry the ball off its wall a little more at
    // every strike. One step of iterative refinement (the same problem for
    // what is left) takes that back to rounding of rounding. A strike that
    // left every active row on its target to its inputs' rounding (most: a
    // pile's strikes are not wedges) has nothing to refine.
    if (!misses_a_target(s, velocity, target)) return s.x.back();
    const Solution refined = solve_island(world, balls, strike, velocity, target, e, &rest_speed);
    apply_impulses(world, refined);
    leave(refined, true);
    return s.x.back() + refined.x.back() + refined.strike_impulse;
  }

  // Every ball of the island `balls` takes its own acceleration plus its
  // contact forces; contacts that would pull leave. The forces depend on
  // the contacts' normals, the masses, the balls' own accelerations and which
  // partners move, never on velocities: an island none of whose balls has
  // gained or lost a contact or changed its mobility since its forces were
  // last found keeps them (the same problem, the same answer).
  // A contact left without force whose relative normal acceleration apart
  // is below `keep_below` (the least press, rest.hpp: rounding, not a
  // parting) stays, with no force: let go, its pair is met again at once
  // (a ball pinched between two sleepers on one line, its second contact
  // redundant, made and let go at one instant for ever).
  void forces(World<Num>& world, const std::vector<int>& balls, const Num& keep_below = Num{}) {
    if (std::none_of(balls.begin(), balls.end(), [&](int x) { return changed_[x] != 0; })) return;
    for (int x : balls) changed_[x] = 0;
    auto own = [&](int x) { return own_acceleration(world.balls[x]); };
    const Solution s = solve_island(world, balls, nullptr, own, Num{}, Num{}, nullptr);
    for (int x : balls) world.balls[x].acceleration = own_acceleration(world.balls[x]);
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      const PersistentContact<Num>& c = s.rows[r];
      auto add = [](Body<Num>& b, const Vec2<Num>& da) { b.acceleration = b.acceleration + da; };
      push(world.balls[c.i], s.x[r] * c.normal, add);
      if (!c.with_wall()) push(world.balls[c.j], -(s.x[r] * c.normal), add);
    }
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      auto at = std::lower_bound(contacts_.begin(), contacts_.end(), s.rows[r],
                                 [](const PersistentContact<Num>& x, const PersistentContact<Num>& y) { return x.key() < y.key(); });
      at->force = s.active[r] ? s.x[r] : Num{};
    }
    erase_rows(s, s.rows.size(), [&](std::size_t r) { return !s.active[r] && !(lcp_.residual(r) < keep_below); });
  }

  // What ball i carries: its own acceleration plus the pushes of the moving
  // balls it touches (the forces of walls and static balls left out).
  Vec2<Num> load(const World<Num>& world, int i) const {
    const Body<Num>& b = world.balls[i];
    Vec2<Num> load = b.free_acceleration;
    if (b.is_static()) return load;
    for (int c : listed(i)) {
      const PersistentContact<Num>& k = contacts_[c];
      const int partner = k.partner_of(i);
      if (partner < 0 || world.balls[partner].is_static()) continue;
      load = load + (k.force / b.mass) * (i == k.i ? k.normal : -k.normal);
    }
    return load;
  }

  void save(ByteWriter& out) const {
    out.put(static_cast<std::uint64_t>(contacts_.size()));
    for (const PersistentContact<Num>& c : contacts_) {
      for (int v : {c.i, c.j, c.wall, static_cast<int>(c.feature)}) out.put(static_cast<std::int32_t>(v));
      out.put(c.normal);
      out.put(c.origin);
      out.put(c.lo);
      out.put(c.hi);
      out.put(c.force);
    }
    // Which islands' forces are still good: a resumed run re-solves exactly
    // those the uninterrupted one would have (the same answer either way,
    // but the solve counters, and so the checkpoint bytes, must agree).
    out.put(static_cast<std::uint64_t>(changed_.size()));
    for (char x : changed_) out.put(static_cast<std::uint8_t>(x != 0));
  }
  // A checkpoint is a file's bytes: every index is checked before use
  // (`walls`: the scene's number of walls).
  void load(ByteReader& in, std::size_t walls) {
    std::uint64_t n = 0;
    in.get(n);
    if (n > in.remaining() / 16) throw std::runtime_error("checkpoint holds more contacts than it has bytes for");
    contacts_.assign(n, {});
    const auto ball_count = static_cast<std::int64_t>(of_ball_.size());
    for (PersistentContact<Num>& c : contacts_) {
      std::int32_t v[4] = {};
      for (std::int32_t& x : v) in.get(x);
      const bool with_wall = v[1] < 0;
      const bool valid = v[0] >= 0 && v[0] < ball_count && v[3] >= static_cast<std::int32_t>(ContactFeature::ball) &&
                         v[3] <= static_cast<std::int32_t>(ContactFeature::wall_end_b) &&
                         (with_wall ? v[1] == -1 && v[2] >= 0 && static_cast<std::uint64_t>(v[2]) < walls &&
                                          v[3] != static_cast<std::int32_t>(ContactFeature::ball)
                                    : v[1] < ball_count && v[1] != v[0] && v[2] == -1);
      if (!valid) throw std::runtime_error("checkpoint holds a contact of no ball or wall of the scene");
      c.i = v[0], c.j = v[1], c.wall = v[2], c.feature = static_cast<ContactFeature>(v[3]);
      in.get(c.normal);
      in.get(c.origin);
      in.get(c.lo);
      in.get(c.hi);
      in.get(c.force);
    }
    std::uint64_t balls = 0;
    in.get(balls);
    if (balls != of_ball_.size()) throw std::runtime_error("checkpoint holds a contact graph of another number of balls");
    parted_.clear();
    for (char& x : changed_) {
      std::uint8_t flag = 0;
      in.get(flag);
      x = static_cast<char>(flag != 0);
    }
    rebuild();
  }

 private:
  std::vector<PersistentContact<Num>> contacts_;  // sorted by key()
  std::vector<PersistentContact<Num>> removed_;   // removed while keeping_removed_ (a trial impact)
  bool keeping_removed_ = false;
  // Every ball's contacts (indices into contacts_, in increasing order) are
  // listed_[start, start + count): a span of two ints a ball, not a vector of
  // three words (most balls of a gas never touch anything).
  struct Span {
    int start = 0, count = 0;
  };
  std::vector<Span> of_ball_;
  std::vector<int> listed_;
  std::vector<int> indexed_;   // the balls whose spans in of_ball_ are not empty
  std::vector<char> changed_;  // per ball: a contact came or went, or its mobility changed, since its island's forces
  std::vector<int> parted_;    // the balls of the contacts removed since the engine last took them (parted())
  mutable std::vector<std::uint32_t> seen_;  // island(): the stamp of the search that last saw each ball
  mutable std::uint32_t stamp_ = 0;
  mutable std::vector<int> stack_;           // island(): the search's stack
  std::vector<int> mine_;                    // solve_island(): the island's contacts, storage reused
  std::vector<char> mine_marks_;             // solve_island(): which contacts are the island's
  Lcp<Num> lcp_;                             // solve_island(): the problem, its storage reused
  std::vector<std::ptrdiff_t> row_slots_;    // solve_island(): each row's balls' places in the island
  std::vector<std::size_t> rows_of_start_, rows_of_;  // solve_island(): the rows of each ball, ball by ball
  std::vector<std::size_t> next_of_;                  // solve_island(): where each ball's next row goes while listing

  struct Solution {
    std::vector<PersistentContact<Num>> rows;  // the island's contacts, then the strike, if any
    std::vector<Num> x;
    std::vector<char> active;
    Num strike_impulse{};                           // of a strike along the held contacts' free part
    std::vector<std::pair<int, Vec2<Num>>> kick;   // its velocity changes, ball by ball
    std::vector<std::pair<int, Vec2<Num>>> free_part;  // its direction d̂, ball by ball
  };

  void mark(const PersistentContact<Num>& c) {
    changed_[c.i] = 1;
    if (!c.with_wall()) changed_[c.j] = 1;
  }

  typename std::vector<PersistentContact<Num>>::iterator first_not_before(const PersistentContact<Num>& c) {
    return std::lower_bound(contacts_.begin(), contacts_.end(), c,
                            [](const PersistentContact<Num>& x, const PersistentContact<Num>& y) { return x.key() < y.key(); });
  }

  // Takes `gone` out of the list, not yet out of the balls' lists (reindex):
  // a solve that lets many contacts go indexes once.
  void erase(const PersistentContact<Num>& gone) {
    const auto at = first_not_before(gone);
    if (at != contacts_.end() && at->key() == gone.key()) {
      if (keeping_removed_) removed_.push_back(*at);
      contacts_.erase(at);
    }
    mark(gone);
    parted_.push_back(gone.i);
    if (!gone.with_wall()) parted_.push_back(gone.j);
  }

  // Every ball's list of its contacts (indices into contacts_, which shift
  // when one comes or goes). Only balls that had or have contacts are touched.
  void reindex() {
    for (int x : indexed_) of_ball_[static_cast<std::size_t>(x)] = {};
    indexed_.clear();
    // Count each ball's contacts, give each ball its stretch, then fill the
    // stretches in contact order.
    for (const PersistentContact<Num>& c : contacts_)
      for (int x : {c.i, c.j}) {
        if (x < 0) continue;
        if (of_ball_[static_cast<std::size_t>(x)].count++ == 0) indexed_.push_back(x);
      }
    int total = 0;
    for (int x : indexed_) {
      Span& span = of_ball_[static_cast<std::size_t>(x)];
      span.start = total;
      total += span.count;
      span.count = 0;
    }
    listed_.resize(static_cast<std::size_t>(total));
    for (int c = 0; c < static_cast<int>(contacts_.size()); ++c)
      for (int x : {contacts_[c].i, contacts_[c].j}) {
        if (x < 0) continue;
        Span& span = of_ball_[static_cast<std::size_t>(x)];
        listed_[static_cast<std::size_t>(span.start + span.count++)] = c;
      }
  }
  std::span<const int> listed(int x) const {
    const Span& span = of_ball_[static_cast<std::size_t>(x)];
    return {listed_.data() + span.start, static_cast<std::size_t>(span.count)};
  }
  void rebuild() {
    std::sort(contacts_.begin(), contacts_.end(),
              [](const PersistentContact<Num>& x, const PersistentContact<Num>& y) { return x.key() < y.key(); });
    reindex();
  }

  template <class Apply>
  static void push(Body<Num>& b, const Vec2<Num>& f, Apply apply) {
    if (!b.is_static()) apply(b, (num<Num>(1.0) / b.mass) * f);
  }

  template <class Quantity>
  static Num relative_normal(const PersistentContact<Num>& c, Quantity q) {
    return c.with_wall() ? dot(c.normal, q(c.i)) : dot(c.normal, q(c.i)) - dot(c.normal, q(c.j));
  }

  void apply_impulses(World<Num>& world, const Solution& s) {
    for (std::size_t r = 0; r < s.rows.size(); ++r) {
      const PersistentContact<Num>& c = s.rows[r];
      push(world.balls[c.i], s.x[r] * c.normal, [](Body<Num>& b, const Vec2<Num>& dv) { b.velocity = b.velocity + dv; });
      if (!c.with_wall())
        push(world.balls[c.j], -(s.x[r] * c.normal), [](Body<Num>& b, const Vec2<Num>& dv) { b.velocity = b.velocity + dv; });
    }
    for (const auto& [ball, dv] : s.kick) world.balls[ball].velocity = world.balls[ball].velocity + dv;
  }

  // Contacts a solution left inactive (they part or let go) leave the graph.
  void leave(const Solution& s, bool has_strike) {
    erase_rows(s, s.rows.size() - (has_strike && !s.rows.empty() ? 1 : 0), [&](std::size_t r) { return !s.active[r]; });
  }

  // Erases the first `count` rows of s that `leaves` picks, then indexes once.
  template <class Leaves>
  void erase_rows(const Solution& s, std::size_t count, Leaves leaves) {
    bool removed = false;
    for (std::size_t r = 0; r < count; ++r)
      if (leaves(r)) erase(s.rows[r]), removed = true;
    if (removed) reindex();
  }

  // The island's LCP for the quantity q (velocity or own acceleration);
  // the strike, if any, is held to w = q_n − strike_target = 0.
  // With `hold_below`, contacts let go slower than it are held (see impact):
  // the pivoting holds each as a round meets it (Lcp::holds), where a whole
  // solve per round of holds took 4.4 solves a strike on a pile of 120
  // (pile_120_e050), up to a dozen; what the pivoting's polish and finish
  // leave parting slowly is held by the loop below, solved again.
  template <class Quantity>
  Solution solve_island(const World<Num>& world, const std::vector<int>& balls, const PersistentContact<Num>* strike,
                        Quantity q, const Num& strike_target, const Num& e, const Num* hold_below) {
    Solution s;
    // The island's contacts are those of its balls, in the graph's (key) order.
    // An island holding more than an eighth of the graph's contacts (a
    // pile's) takes them marked and read in order, cheaper than sorting.
    std::vector<int>& mine = mine_;
    mine.clear();
    for (int x : balls) {
      const std::span<const int> of_x = listed(x);
      mine.insert(mine.end(), of_x.begin(), of_x.end());
    }
    if (mine.size() * 4 < contacts_.size()) {  // each contact listed once or twice
      std::sort(mine.begin(), mine.end());
      mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    } else {
      mine_marks_.assign(contacts_.size(), 0);
      for (int c : mine) mine_marks_[static_cast<std::size_t>(c)] = 1;
      mine.clear();
      for (std::size_t c = 0; c < mine_marks_.size(); ++c)
        if (mine_marks_[c]) mine.push_back(static_cast<int>(c));
    }
    for (int c : mine)
      if (!(strike && contacts_[c].key() == strike->key())) s.rows.push_back(contacts_[c]);  // the strike: the last row
    if (strike) s.rows.push_back(*strike);
    const std::size_t k = s.rows.size();
    Lcp<Num>& lcp = lcp_;
    lcp.reset(k);
    // Rows couple only through a ball they share (A_cd = 0 otherwise): each
    // row is paired with the rows of its own balls, listed per ball of the
    // island in increasing order (rows_of_start_: where each ball's list
    // begins in rows_of_; storage kept from one solve to the next).
    auto slot = [&](int x) {
      const auto at = std::lower_bound(balls.begin(), balls.end(), x);
      return at != balls.end() && *at == x ? static_cast<std::ptrdiff_t>(at - balls.begin()) : -1;
    };
    std::vector<std::ptrdiff_t>& slots = row_slots_;  // per row, its two balls' places (−1: none)
    slots.resize(2 * k);
    std::vector<std::size_t>& start = rows_of_start_;
    start.assign(balls.size() + 1, 0);
    for (std::size_t r = 0; r < k; ++r)
      for (int side = 0; side < 2; ++side) {
        const int x = side == 0 ? s.rows[r].i : s.rows[r].j;
        slots[2 * r + side] = x < 0 ? -1 : slot(x);
        if (slots[2 * r + side] >= 0) ++start[static_cast<std::size_t>(slots[2 * r + side]) + 1];
      }
    for (std::size_t x = 0; x < balls.size(); ++x) start[x + 1] += start[x];
    std::vector<std::size_t>& rows_of = rows_of_;
    rows_of.resize(start.back());
    next_of_.assign(start.begin(), start.end() - 1);
    for (std::size_t r = 0; r < k; ++r)
      for (int side = 0; side < 2; ++side)
        if (const std::ptrdiff_t at = slots[2 * r + side]; at >= 0) rows_of[next_of_[static_cast<std::size_t>(at)]++] = r;
    for (std::size_t r = 0; r < k; ++r) {
      const PersistentContact<Num>& c = s.rows[r];
      const Vec2<Num> qi = q(c.i), qj = c.with_wall() ? Vec2<Num>{} : q(c.j);
      lcp.b[r] = dot(c.normal, qi) - dot(c.normal, qj);
      lcp.size[r] = NumberTraits<Num>::sqrt(length_squared(qi)) + NumberTraits<Num>::sqrt(length_squared(qj));
      for (int side = 0; side < 2; ++side)
        if (const std::ptrdiff_t at = slots[2 * r + side]; at >= 0)
          for (std::size_t n = start[static_cast<std::size_t>(at)]; n < start[static_cast<std::size_t>(at) + 1]; ++n)
            lcp.set(r, rows_of[n], coupling(world, c, s.rows[rows_of[n]]));
    }
    if (strike) {
      // The strike comes last and is solved whatever its pivot (an
      // equation, not a contact that may be redundant), so a ball struck in
      // a wedge the width of its diameter bounces back along its wall.
      lcp.b[k - 1] = lcp.b[k - 1] - strike_target;  // w = v_n' − target = 0
      lcp.equality[k - 1] = 1;
      lcp.forced = k - 1;
    }
    auto count_solve = [&] {  // an island without contacts (a gas's collision) has no problem to count
      if (k == 0) return;
      ++(hold_below ? solve_counters.impact_solves : solve_counters.force_solves);
      solve_counters.rows += k;
      if (solve_counters.largest < k) solve_counters.largest = k;
    };
    count_solve();
    if (hold_below) lcp.holds = true, lcp.hold_below = *hold_below;
    std::size_t singular = lcp.solve();
    while (hold_below && singular == k) {
      bool held = false;
      for (std::size_t r = 0; r < k; ++r) {
        if (lcp.active[r]) continue;
        if (lcp.residual(r) < *hold_below) lcp.equality[r] = lcp.active[r] = 1, held = true;
      }
      if (!held) break;
      count_solve();
      singular = lcp.solve();
    }
    if (k > 0) solve_counters.rounds += lcp.rounds;
    s.active = lcp.active;
    if (singular < k) {
      s.x.assign(k, Num{});
      strike_along_free_part(world, lcp, q, e, s);
    } else {
      s.x = lcp.x;
    }
    return s;
  }

  // The strike's normal lies in the span of the held contacts' normals, to
  // rounding (a wedge whose two walls are parallel to ε): in impulses the
  // answer is of order v/ε and cancels to v, which no number type carries.
  // In velocities it is plain: the held contacts leave free only the part
  // d = j_s − J_Hᵀ α of the strike's direction j_s that is M⁻¹-orthogonal
  // to theirs (A_HH α = A_Hs), and the strike acts along d alone,
  //     Δv = M⁻¹ d P,  P = −w_s / (d M⁻¹ d),
  // with w_s = j_s·v + e j_s·v the strike's miss (j_s M⁻¹ d = d M⁻¹ d), so
  // the held contacts keep their speeds (J_H M⁻¹ d = 0). As they are held,
  // J_H v = 0 and j_s·v = d·v: the strike is the textbook reflection along
  // d̂ = d / (its largest component), Δ(d̂·v) = −(1 + e) d̂·v, computed from
  // d̂ alone (d and j_s·v are of order ε, rounding's size). For one ball
  // sliding on a wall into a wedge this is the reflection along the wall,
  // u' = −e u.
  template <class Quantity>
  void strike_along_free_part(const World<Num>& world, const Lcp<Num>& lcp, Quantity velocity, const Num& e,
                              Solution& s) const {
    const std::size_t k = s.rows.size();
    std::vector<std::size_t> held;
    for (std::size_t r = 0; r + 1 < k; ++r)
      if (lcp.active[r]) held.push_back(r);
    Lcp<Num> projection(held.size());
    for (std::size_t a = 0; a < held.size(); ++a) {
      for (std::size_t c = 0; c < held.size(); ++c) projection.set(a, c, lcp.a(held[a], held[c]));
      projection.b[a] = -lcp.a(held[a], k - 1);
      projection.size[a] = lcp.a(held[a], held[a]);
      projection.equality[a] = 1;
    }
    projection.solve();
    // d per ball, in the order the balls appear in the rows.
    auto direction_of = [](const PersistentContact<Num>& c, int x) { return x == c.i ? c.normal : -c.normal; };
    const PersistentContact<Num>& strike = s.rows[k - 1];
    std::vector<std::pair<int, Vec2<Num>>> d;
    auto add = [&](int x, const Vec2<Num>& v) {
      if (x < 0 || world.balls[x].is_static()) return;
      for (auto& [ball, dx] : d)
        if (ball == x) return void(dx = dx + v);
      d.push_back({x, v});
    };
    add(strike.i, strike.normal);
    if (!strike.with_wall()) add(strike.j, -strike.normal);
    for (std::size_t a = 0; a < held.size(); ++a) {
      const PersistentContact<Num>& c = s.rows[held[a]];
      add(c.i, -(projection.x[a] * direction_of(c, c.i)));
      if (!c.with_wall()) add(c.j, -(projection.x[a] * direction_of(c, c.j)));
    }
    auto magnitude = [](const Num& v) { return NumberTraits<Num>::abs(v); };
    Num largest{}, rounding = num<Num>(1.0);
    for (const auto& [ball, dx] : d)
      for (const Num& component : {dx.x, dx.y})
        if (largest < magnitude(component)) largest = magnitude(component);
    for (std::size_t a = 0; a < held.size(); ++a) rounding = rounding + magnitude(projection.x[a]);
    // d is a difference of unit normals weighted 1 and α: below 2^-40 of
    // their weight it is rounding, no direction at all. The held contacts
    // then answer the strike alone: it is not closing (j_s·v = αᵀ J_H v, and
    // they are held), nothing moves.
    if (!(num<Num>(0x1p-40) * rounding < largest)) return;
    Num stiffness{}, speed{};  // d̂ M⁻¹ d̂ and d̂·v
    for (auto& [ball, dx] : d) {
      dx = Vec2<Num>{dx.x / largest, dx.y / largest};  // each ≤ 1: no overflow, where 1 / largest may
      stiffness = stiffness + length_squared(dx) / world.balls[ball].mass;
      speed = speed + dot(dx, velocity(ball));
    }
    const Num impulse = -((num<Num>(1.0) + e) * speed) / stiffness;
    s.strike_impulse = impulse;  // along d̂ (along j_s it would be impulse / largest, of order v/ε)
    for (const auto& [ball, dx] : d) s.kick.push_back({ball, (impulse / world.balls[ball].mass) * dx});
    s.free_part = d;
  }

  // After a strike's impulses (s, its strike the last row): does an active
  // row miss its target, zero or the strike's −e v_n, or an inactive one
  // sink, by more than 2^-40 of its speeds (for a number type that rounds
  // to an absolute step, plus 16 of its steps)? Stricter than the
  // pivoting's own tolerance (lcp.hpp, which also allows 2^-40 of the
  // problem's largest row and four steps a term): a strike it flags that
  // the pivoting would have passed is only refined once more.
  template <class Quantity>
  static bool misses_a_target(const Solution& s, Quantity velocity, const Num& target) {
    const std::size_t k = s.rows.size();
    for (std::size_t r = 0; r < k; ++r) {
      const PersistentContact<Num>& c = s.rows[r];
      const Vec2<Num> vi = velocity(c.i), vj = c.with_wall() ? Vec2<Num>{} : velocity(c.j);
      const Num aim = r + 1 == k ? target : Num{};
      const Num w = dot(c.normal, vi) - dot(c.normal, vj) - aim;
      const Num miss = s.active[r] ? NumberTraits<Num>::abs(w) : -w;  // an inactive row may part (w > 0)
      const Num speeds = NumberTraits<Num>::sqrt(length_squared(vi)) + NumberTraits<Num>::sqrt(length_squared(vj)) +
                         NumberTraits<Num>::abs(aim);
      Num tolerance = num<Num>(0x1p-40) * speeds;
      if constexpr (NumberTraits<Num>::rounds_absolutely)
        tolerance = tolerance + num<Num>(16.0) * NumberTraits<Num>::resolution();
      if (tolerance < miss) return true;
    }
    return false;
  }

  // A_cd: the normal acceleration of contact c per unit force of contact d.
  static Num coupling(const World<Num>& world, const PersistentContact<Num>& c, const PersistentContact<Num>& d) {
    Num sum{};
    for (int x : {c.i, c.j}) {
      if (x < 0 || (x != d.i && x != d.j) || world.balls[x].is_static()) continue;
      const Vec2<Num> nc = x == c.i ? c.normal : -c.normal;
      const Vec2<Num> nd = x == d.i ? d.normal : -d.normal;
      sum = sum + dot(nc, nd) / world.balls[x].mass;
    }
    return sum;
  }
};

}  // namespace collide2d
