// What happens at a contact: the response (reflection, the n–t impulse, an
// island's impact) and the rest rules of rest.hpp (a contact made, the sleep
// test, creep). The engine (event_engine.hpp) decides *when*; this decides
// *what*, and counts what each rule did and the energy it took.
#pragma once

#include <span>
#include <vector>

#include "collide2d/response/response.hpp"
#include "collide2d/sim/cell_grid.hpp"
#include "collide2d/sim/contact_graph.hpp"
#include "collide2d/sim/event_queue.hpp"
#include "collide2d/sim/pinch.hpp"
#include "collide2d/sim/rest.hpp"
#include "collide2d/sim/world.hpp"

namespace collide2d {

// The unit normal of wall face w on the side of point p.
template <class Num>
Vec2<Num> face_normal_towards(const WallGeometry<Num>& w, const Vec2<Num>& p) {
  const Num side = cross(w.direction.hi, p - w.segment.a);
  return side < Num{} ? -w.unit_normal : w.unit_normal;
}

// The unit normal, towards a ball centred at p, of its contact with feature
// f of wall w (its face, or one of its round ends).
template <class Num>
Vec2<Num> wall_contact_normal(const WallGeometry<Num>& w, ContactFeature f, const Vec2<Num>& p) {
  if (f == ContactFeature::wall_face) return face_normal_towards(w, p);
  return normalized(p - (f == ContactFeature::wall_end_a ? w.segment.a : w.segment.b));
}

// Rule 5's test (ContactRules::creeping): nothing presses the contact of
// normal n together (n·Δa ≥ −least press) and it closes slower than the
// creep speed.
template <class Num>
bool is_creeping(const Vec2<Num>& n, const Vec2<Num>& relative_velocity, const Vec2<Num>& relative_acceleration,
                 const RestThresholds<Num>& th) {
  return !(dot(n, relative_acceleration) < -th.least_press) && -dot(n, relative_velocity) < th.creep_speed;
}

// The point of wall w nearest to p, and which feature it is on.
template <class Num>
Vec2<Num> nearest_point(const WallGeometry<Num>& w, const Vec2<Num>& p, ContactFeature* feature = nullptr) {
  const Num zero{};
  const Num along = dot(w.direction.hi, p - w.segment.a);
  ContactFeature f = ContactFeature::wall_face;
  Vec2<Num> q;
  if (!(zero < along)) {
    q = w.segment.a, f = ContactFeature::wall_end_a;
  } else if (!(along < w.length_squared)) {
    q = w.segment.b, f = ContactFeature::wall_end_b;
  } else {
    const Vec2<Num> n = face_normal_towards(w, p);  // the foot of the perpendicular
    q = p - dot(p - w.segment.a, n) * n;
  }
  if (feature) *feature = f;
  return q;
}

template <class Num>
class ContactRules {
 public:
  explicit ContactRules(const RestThresholds<Num>& th)
      : th_(th), sqrt_height_(NumberTraits<Num>::sqrt(th.height)),
        jam_speed_(th.speed == Num{} ? th.creep_speed : th.speed) {}

  const RestThresholds<Num>& thresholds() const { return th_; }
  RestCounters counters;
  Num energy_removed{};  // kinetic energy taken by contacts made (rule 1) and sleep

  // sqrt(2 g_n h_rest): the speed that rises h_rest against g_n. Formed as
  // sqrt(2 g_n) sqrt(h_rest) so that fixed point cannot round a tiny product
  // to zero.
  Num hop_speed(const Num& g_n) const { return NumberTraits<Num>::sqrt(num<Num>(2.0) * g_n) * sqrt_height_; }

  // Rule 1: the slowest parting kept by a held pair whose relative normal
  // acceleration is `pressing` (< 0: pressed together): v_rest (without
  // gravity, the creep speed), and pressed, the speed that rises h_rest.
  Num rebound_limit(const Num& pressing) const {
    if (!(pressing < -th_.least_press)) return jam_speed_;
    const Num hop = hop_speed(-pressing);
    return hop < jam_speed_ ? jam_speed_ : hop;
  }

  // Rule 3: a strike this fast wakes a sleeping ball.
  bool wakes(const Num& closing) const { return !(closing < th_.speed); }

  // Rule 5 (creep): a contact nothing presses together (n·Δa ≥ −least
  // press: less is rounding, rest.hpp), closing
  // slower than the creep speed, is not processed: in a row of balls jammed
  // between walls every impulse would at once cause another at the same
  // instant, without end. The pair is predicted again when either ball's
  // motion next changes.
  bool creeping(const Vec2<Num>& n, const Vec2<Num>& relative_velocity, const Vec2<Num>& relative_acceleration) {
    if (!is_creeping(n, relative_velocity, relative_acceleration, th_)) return false;
    ++counters.creeping;
    return true;
  }

  // Rule 2: slower than v_rest and carried by its static supports.
  bool can_sleep(const World<Num>& world, const CellGrid<Num>& grid, const ContactGraph<Num>& graph, int i) const {
    const Body<Num>& b = world.balls[i];
    if (b.is_static() || !(length_squared(b.velocity) < th_.speed * th_.speed)) return false;
    if (b.free_acceleration.x == Num{} && b.free_acceleration.y == Num{}) return false;  // no weight to carry
    return carried(world, grid, graph, i);
  }

  // Rule 2 for an island of balls in contact: every one slower than v_rest,
  // and the island's contact forces (λ ≥ 0, solved by contact_graph.hpp)
  // hold every one still (|a| below the least press): the static
  // equilibrium of McNamara & Herrmann, found, not assumed.
  bool island_can_sleep(const World<Num>& world, const std::vector<int>& island) const {
    if (island.empty()) return false;
    const Num least = th_.least_press * th_.least_press;
    for (int x : island) {
      const Body<Num>& b = world.balls[x];
      if (!(length_squared(b.velocity) < th_.speed * th_.speed) || least < length_squared(b.acceleration)) return false;
      if (b.free_acceleration.x == Num{} && b.free_acceleration.y == Num{}) return false;  // no weight to carry
    }
    return true;
  }

  // The load on ball i (its weight plus the pushes of the moving balls it
  // touches: contact_graph.hpp) lies in the cone of the normals of the walls
  // and static balls within the contact band (rest.hpp, rule 2).
  bool carried(const World<Num>& world, const CellGrid<Num>& grid, const ContactGraph<Num>& graph, int i) const {
    const Body<Num>& b = world.balls[i];
    std::vector<Vec2<Num>> normals;
    for (const WallGeometry<Num>& w : world.walls) {
      const Vec2<Num> q = nearest_point(w, b.position);
      const Num reach = b.radius + th_.band;
      if (!(reach * reach < length_squared(b.position - q))) normals.push_back(normalized(b.position - q));
    }
    grid.for_each_neighbour(i, [&](int j) {
      const Body<Num>& s = world.balls[j];
      if (j == i || !s.is_static()) return;
      if (within_band(b, s)) normals.push_back(normalized(b.position - s.position));
    });
    return carried_by(graph.load(world, i), normals);
  }

  // Ball s is near enough to ball b to be one of its supports: their gap is
  // within the contact band δ.
  bool within_band(const Body<Num>& b, const Body<Num>& s) const {
    const Num reach = b.radius + s.radius + th_.band;
    return !(reach * reach < length_squared(b.position - s.position));
  }

  void put_to_sleep(Body<Num>& b) {
    energy_removed = energy_removed + kinetic_energy(b);
    b.velocity = {};
    b.acceleration = {};
    b.asleep = true;
    ++counters.fell_asleep;
  }

  // The island `balls` takes the impulses that stop its contacts' normal
  // velocities (a partner of theirs fell asleep); the energy is counted.
  void hold(World<Num>& world, ContactGraph<Num>& graph, const std::vector<int>& balls) {
    const Num before = kinetic_energy_of(world, balls);
    graph.impact(world, balls, nullptr, Num{}, th_.speed);
    energy_removed = energy_removed + (before - kinetic_energy_of(world, balls));
  }

  static Num kinetic_energy_of(const World<Num>& world, const std::vector<int>& balls) {
    Num sum{};
    for (int x : balls) sum = sum + kinetic_energy(world.balls[x]);
    return sum;
  }
  // The balls whose velocities the last collide() or renew() changed: the
  // engine gives each a new version (its old predictions are stale) and
  // tells its observer (event_engine.hpp).
  const std::vector<int>& moved_balls() const { return moved_; }

  static void wake(Body<Num>& b) {
    b.asleep = false;
    b.acceleration = b.free_acceleration;
  }

  // The response of a strike on balls out of contact (n from the partner b,
  // or a wall if b is null, towards a): an immovable partner reflects the
  // mover, two moving balls take the n–t impulse. Returns the impulse on the
  // mover along its normal (on a, for two balls).
  // (B: a Body, or a gas's one-line body, gas_world.hpp.)
  template <class B>
  static Num textbook_response(B& a, B* b, bool a_moves, bool b_moves, const Vec2<Num>& n, const Num& restitution) {
    if (a_moves && b_moves) {
      const TwoBallVelocities<Num> out = two_ball_impulse_response(a.velocity, b->velocity, a.mass, b->mass, n, restitution);
      a.velocity = out.v1;
      b->velocity = out.v2;
      return out.impulse;
    }
    B& mover = a_moves ? a : *b;
    const Vec2<Num> normal = a_moves ? n : -n;
    const Vec2<Num> v = mover.velocity;
    mover.velocity = reflect_velocity(v, normal, restitution);
    return mover.mass * dot(mover.velocity - v, normal);
  }

  // The contact that ball e.a meeting its partner (ball e.b, or wall e.b
  // at e.feature) would make; n is the unit normal at it, towards e.a.
  PersistentContact<Num> contact_for(const World<Num>& world, const Event<Num>& e, const Vec2<Num>& n) const {
    PersistentContact<Num> c;
    const Body<Num>& a = world.balls[e.a];
    c.i = e.a;
    c.normal = n;
    const Vec2<Num> t = tangent_of(n);
    if (e.kind == EventKind::ball_ball) {
      const Body<Num>& b = world.balls[e.b];
      c.j = e.b;
      c.origin = a.position - b.position;
      c.hi = slide_length(a.radius + b.radius, th_.height);
      c.lo = -c.hi;
      return c;
    }
    const WallGeometry<Num>& w = world.walls[e.b];
    c.wall = e.b;
    c.origin = a.position;
    // On the face, between its ends, the ball slides along the face to
    // either end; anywhere else (an end, or a face contact a hair past an
    // end) along the tangent at the nearer end.
    const Num along = dot(w.direction.hi, a.position - w.segment.a);
    if (e.feature == ContactFeature::wall_face && Num{} < along && along < w.length_squared) {
      c.feature = ContactFeature::wall_face;
      const Num at_a = dot(t, w.segment.a - a.position), at_b = dot(t, w.segment.b - a.position);
      c.lo = at_a < at_b ? at_a : at_b;
      c.hi = at_a < at_b ? at_b : at_a;
    } else {
      c.feature = along < NumberTraits<Num>::half(w.length_squared) ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
      c.hi = slide_length(a.radius, th_.height);
      c.lo = -c.hi;
    }
    return c;
  }

  // Face contact c has slid past an end of its wall: the ball touches the
  // round end there, with the face's normal, and slides on along the same
  // line for ±L before it has risen h_rest off the end.
  PersistentContact<Num> onto_the_end(const World<Num>& world, const PersistentContact<Num>& c) const {
    PersistentContact<Num> end = c;
    const Body<Num>& a = world.balls[c.i];
    const WallGeometry<Num>& w = world.walls[c.wall];
    const Num along = dot(w.direction.hi, a.position - w.segment.a);
    end.feature = along < NumberTraits<Num>::half(w.length_squared) ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
    end.origin = a.position;
    end.hi = slide_length(a.radius, th_.height);
    end.lo = -end.hi;
    return end;
  }

  // The round partner of contact c (not a face): the centre of the partner
  // ball, or the wall's end, and the contact distance R.
  struct RoundPartner {
    Vec2<Num> centre;
    Num R;
    bool ball;
  };
  static RoundPartner round_partner(const World<Num>& world, const PersistentContact<Num>& c) {
    const Body<Num>& a = world.balls[c.i];
    if (!c.with_wall()) return {world.balls[c.j].position, a.radius + world.balls[c.j].radius, true};
    const WallGeometry<Num>& w = world.walls[c.wall];
    return {c.feature == ContactFeature::wall_end_a ? w.segment.a : w.segment.b, a.radius, false};
  }

  // Contact c with a round partner goes on along the tangent of unit normal
  // n: its origin is the tangent point R n (from the partner's centre), and
  // its range ±L about it, widened to hold the offset where the ball is now.
  // That offset is formed as predict_contact_ending forms it (p_i − p_j −
  // origin for two balls, p_i − origin against a wall), so that the range
  // holds it to the last bit: one rounding outside, the contact would end
  // at once and be renewed the same, for ever (a held-out hopper stalled).
  void along_tangent_at(PersistentContact<Num>& c, const Vec2<Num>& n, const World<Num>& world,
                        const RoundPartner& round) const {
    const Vec2<Num>& position = world.balls[c.i].position;
    const Vec2<Num> touch = round.R * n;  // the offset at the tangent point
    c.normal = n;
    c.origin = round.ball ? touch : round.centre + touch;
    const Num L = slide_length(round.R, th_.height);
    const Num here = dot(tangent_of(n), round.ball ? (position - round.centre) - touch : position - c.origin);
    c.lo = here < -L ? here : -L;
    c.hi = L < here ? here : L;
  }

  // Rule 1 again where a contact with a round partner (a ball, a wall's
  // end) has slid its length L off (rest.hpp): the offset p, now at distance
  // d = |p| ≈ R + h_rest from the partner's centre, goes on along the old
  // tangent and would part from the circle by a hop. If the pair is pressed
  // together (the forces without the contact already solved: a_n < 0 along
  // the new normal) and that hop, at the parting speed u = n'·Δv ≥ 0, rises
  // less than h_rest, it is collapsed as any other (the plastic impact takes
  // u to zero, at most ½ m u² of energy, counted) and the contact goes on
  // along the tangent from p to the circle: its normal n' points at the
  // tangent point, at angle φ ahead of p with cos φ = R/d, sin φ = ℓ/d,
  // ℓ = sqrt(d² − R²) ≤ L, so the offset runs from ℓ before the tangent
  // point to L past it, never further than h_rest off the circle and never
  // inside it. A sliding contact thus costs one event per 2L of arc, where
  // parting and landing again would cost two per L and more. Balls not
  // pressed together, or parting faster, fly as before. Returns true if the
  // contact was renewed (the caller solves the island's forces again).
  bool renew(World<Num>& world, ContactGraph<Num>& graph, const PersistentContact<Num>& gone, std::vector<int>& changed) {
    const Num zero{};
    if (gone.feature == ContactFeature::wall_face) return false;
    const Body<Num>& a = world.balls[gone.i];
    const Body<Num>* b = gone.with_wall() ? nullptr : &world.balls[gone.j];
    const RoundPartner round = round_partner(world, gone);
    const Vec2<Num>& centre = round.centre;
    const Num& R = round.R;
    const Vec2<Num> p = a.position - centre;
    const Num d2 = length_squared(p), R2 = R * R;
    if (!(R2 < d2)) return false;
    const bool a_moves = !a.is_static(), b_moves = b && !b->is_static();
    auto relative = [&](auto quantity) {
      return (a_moves ? quantity(a) : Vec2<Num>{}) - (b_moves ? quantity(*b) : Vec2<Num>{});
    };
    const Vec2<Num> dv = relative([](const Body<Num>& x) { return x.velocity; });
    const Vec2<Num> da = relative([](const Body<Num>& x) { return x.acceleration; });
    const Num d = NumberTraits<Num>::sqrt(d2), ell = NumberTraits<Num>::sqrt(d2 - R2);
    const Vec2<Num> along_p{p.x / d, p.y / d};
    Vec2<Num> ahead = tangent_of(along_p);
    if (dot(ahead, dv) < zero) ahead = -ahead;
    const Vec2<Num> n = normalized((R / d) * along_p + (ell / d) * ahead);
    const Num u = dot(n, dv), press = dot(n, da);
    if (u < zero || !(press < -th_.least_press) || !(u < hop_speed(-press))) return false;

    PersistentContact<Num> c = gone;
    c.force = zero;
    along_tangent_at(c, n, world, round);

    std::vector<int> seeds;
    if (a_moves) seeds.push_back(gone.i);
    if (b_moves) seeds.push_back(gone.j);
    const std::vector<int> island = graph.island(world, seeds);
    const Num before = kinetic_energy_of(world, island);
    graph.add(c);
    graph.impact(world, island, &c, zero, th_.speed);
    energy_removed = energy_removed + (before - kinetic_energy_of(world, island));
    ++counters.renewed;
    moved(island, changed);
    return true;
  }

  // The collision that makes contact c (not yet in the graph). Balls out of
  // contact take the textbook response (reflection, the n–t impulse); a
  // ball in contact brings its island, which answers at once
  // (contact_graph.hpp). Rule 1 then makes the contact persistent if the
  // rebound is too low to count. Every ball whose motion changed is added to
  // `changed`; the caller solves the islands' forces again.
  // `island`: the moving balls of the islands of c's balls (ContactGraph::
  // island), carried to the present by the caller, who found them to do so.
  // The collision is returned in storage of the rules' own, valid until the
  // next one (a gas allocates nothing per event).
  const Collision<Num>& collide(World<Num>& world, ContactGraph<Num>& graph, const CellGrid<Num>& grid,
                                const Event<Num>& e, const PersistentContact<Num>& struck,
                                std::span<const int> island_of_c, std::vector<int>& changed) {
    const Num zero{};
    PersistentContact<Num> c = struck;
    Body<Num>& a = world.balls[c.i];
    Body<Num>* b = c.with_wall() ? nullptr : &world.balls[c.j];
    const Num restitution = contact_restitution(a.restitution, b ? b->restitution : world.wall_restitution[c.wall]);
    const bool a_moves = !a.is_static(), b_moves = b && !b->is_static();
    int seeds[2];
    int n_seeds = 0;
    if (a_moves) seeds[n_seeds++] = c.i;
    if (b_moves) seeds[n_seeds++] = c.j;
    const std::span<const int> movers(seeds, static_cast<std::size_t>(n_seeds));
    std::vector<int>& island = collision_.island;
    island.assign(island_of_c.begin(), island_of_c.end());
    const bool held = std::any_of(movers.begin(), movers.end(), [&](int x) { return graph.in_contact(x); });
    const bool a_again = a.struck_at == e.time, b_again = b && b->struck_at == e.time;
    const bool again = a_again || b_again;  // jammed: rule 1
    a.struck_at = e.time;
    if (b) b->struck_at = e.time;
    // A lone ball struck again at this instant between two immovable
    // partners a diameter apart is answered along the pinch's axis, and
    // plastically: the limit of its series there (pinch.hpp). In a wedge
    // (a gap narrower than the ball) whose series at this instant
    // collapses, the limit is a plastic impact on both sides at once.
    bool pinched = false;
    std::optional<Pinch> wedge;
    if (n_seeds == 1 && island.size() == 1 && (seeds[0] == c.i ? a_again : b_again) && restitution < Num{1}) {
      const int m = seeds[0];  // struck again itself (a static partner struck by another ball is no jam)
      const Vec2<Num> n = m == c.i ? c.normal : -c.normal;
      if (const auto pinch = find_pinch(world, grid, c, m, n)) {
        c.normal = m == c.i ? pinch->axis : -pinch->axis;
        align_other_side(graph, m, *pinch);
        pinched = true;
      } else if (const auto side = find_wedge(world, grid, c, m, n, restitution)) {
        if (side->opposite) {  // a pinch to the engine, along the struck normal (its axis)
          align_other_side(graph, m, *side);
          pinched = true;
        } else {
          wedge = side;
        }
      }
    }
    auto relative = [&](auto quantity) {
      const Vec2<Num> qa = a_moves ? quantity(a) : Vec2<Num>{}, qb = b_moves ? quantity(*b) : Vec2<Num>{};
      return dot(c.normal, qa - qb);
    };
    Num pressing = relative([](const Body<Num>& x) { return x.acceleration; });  // < 0: pressed together
    std::vector<Vec2<Num>>& before = collision_.island_velocity_before;
    before.clear();
    for (int x : island) before.push_back(world.balls[x].velocity);

    Num impulse{};
    std::vector<std::pair<int, Vec2<Num>>> free_part;  // set if the strike acted along its free part alone
    // A held strike's answer leaves the struck pair parting at its target,
    // e |v_n| (contact_graph.hpp: the strike is an equation): where that is
    // below what rule 1 lets part, the strike is plastic, known before any
    // solve, and the island solves it once rather than twice (pile_120_e050:
    // half of its 93,000 strikes on islands were answered with restitution
    // and then again plastically, 1.34 solves of ~100 rows wasted each). A
    // target within 2^-20 of the limit, where the answer's rounding could
    // decide, and the jammed, pinched and wedged strikes, whose rebound is
    // measured otherwise, still take the trial.
    const Num closing = -relative([](const Body<Num>& x) { return x.velocity; });
    const bool plastic_at_once =
        held && !again && !pinched && !wedge && restitution * closing < rebound_limit(pressing) * num<Num>(1.0 - 0x1p-20);
    if (held) {
      ++counters.held;
      if (!pinched && !wedge) align_round_contacts(world, graph, island);
      if (!plastic_at_once) {
        graph.keep_removed();
        impulse = graph.impact(world, island, &c, restitution, th_.speed, &free_part);
      }
    } else {
      impulse = textbook_response(a, b, a_moves, b_moves, c.normal, restitution);
    }

    // Rule 1: pressed together and rising less than h_rest, they stay; so do
    // a pinched ball and its partner, and a jammed ball, or a ball of an
    // island (held), and its partner parting slower than v_rest (without
    // gravity, the creep speed: over the whole run they part by less than
    // h_rest). A
    // strike the held contacts left only part of its direction to act along
    // (a wedge) rises along that part: that is where rebound and press are
    // measured.
    Num rebound = relative([](const Body<Num>& x) { return x.velocity; });
    if (!free_part.empty()) {
      Num along{}, press{};
      for (const auto& [x, d] : free_part) {
        along = along + dot(d, world.balls[x].velocity);
        press = press + dot(d, world.balls[x].acceleration);
      }
      rebound = along, pressing = press;
    }
    // Too slow to part (rule 1): a held or re-struck pair below rebound_limit,
    // any other pair below the hop speed while pressed.
    const bool too_slow = (again || held) ? rebound < rebound_limit(pressing)
                                          : pressing < -th_.least_press && rebound < hop_speed(-pressing);
    if (plastic_at_once || too_slow || pinched || wedge) {
      const Num bounced = plastic_at_once ? Num{} : kinetic_energy_of(world, island);
      for (std::size_t k = 0; k < island.size(); ++k) world.balls[island[k]].velocity = before[k];
      graph.restore_removed(c);
      graph.add(c);
      if (wedge) hold_other_side(world, graph, island[0], *wedge);
      if (again) {
        // One plastic impact of the struck pair and the touching pairs of
        // every ball of the island struck at this instant, at once
        // (join_touching): no row is forced.
        join_touching(world, graph, island, e.time);
        impulse = graph.impact(world, island, nullptr, zero, th_.speed, nullptr, &c);
      } else {
        impulse = graph.impact(world, island, &c, zero, th_.speed);
      }
      if (pinched) {
        impulse = impulse + stop_closing_on(world, struck, seeds[0]);
        // The contact held with a round partner pushes along the line of
        // centres, not the pinch's axis: along the axis the ball's weight
        // may pull it off (the force solve lets it go) while along the line
        // of centres it presses, and the pair, touching and closing by
        // rounding, meets again at once, for ever (the unseen pile_200_e095
        // at t = 2.4813: a ball falling through a slot its own width,
        // 2.6e-6 rad between axis and line of centres).
        if (struck.feature != ContactFeature::wall_face)
          if (const PersistentContact<Num>* held = struck.with_wall() ? graph.with_wall(struck.i, struck.wall)
                                                                        : graph.find_pair(struck.i, struck.j))
            turn_onto_line_of_centres(world, graph, *held);
      }
      // What the rule took is what the rebound would have carried. Made at
      // once, that is ½ e² v_n P for the plastic impulse P: the answers
      // with and without the restitution differ by the strike's row alone
      // (the held rows start at relative rest), Δλ = A⁻¹ e v_n ê_s, whose
      // energy is ½ (e v_n)² (A⁻¹)_ss, and P = v_n (A⁻¹)_ss. Two free
      // balls: ½ μ (e v_n)².
      energy_removed = energy_removed + (plastic_at_once ? num<Num>(0.5) * restitution * restitution * closing * impulse
                                                         : bounced - kinetic_energy_of(world, island));
      ++(b_moves && a_moves ? counters.plastic_pairs : counters.came_to_rest);
    }
    graph.forget_removed();
    moved(island, changed);
    collision_.time = e.time;
    collision_.kind = e.kind;
    collision_.a = e.a;
    collision_.b = e.b;
    collision_.impulse = impulse;
    return collision_;
  }

 private:
  // A pinch answers along its axis, which may lie off the struck contact's
  // own normal N by up to sqrt(2 gap / r) rad (the gap the pinch admits is
  // wider than the diameter by up to the contact band): a ball moving
  // square to the axis at tangential speed u then still closes on its
  // struck partner at u·α along N, meets it again at once, and the pinch
  // answers with no impulse, for ever (seed 12345 of wake-keeps-momentum,
  // fixed mode: α = 5.6e-7, u α = 3.1e-9, above the creep speed). The limit
  // of that series is a plastic impact along N too: what still closes along
  // N is taken away, v_m ← v_m − (N·v_m) N (the partner is immovable), which
  // only removes energy. It may pass a closing of up to u α to the far side
  // (whose normal is nearly −N); under gravity pressing the ball onto that
  // side, rule 1 then holds it there (the seed-12345 case). Without such a
  // press the exact limit is the projection of v onto the cone of both
  // sides' normals, not made here. Returns the impulse's magnitude.
  Num stop_closing_on(World<Num>& world, const PersistentContact<Num>& struck, int m) const {
    Body<Num>& ball = world.balls[m];
    const Vec2<Num> n = m == struck.i ? struck.normal : -struck.normal;  // from the partner towards m
    const Num closing = dot(n, ball.velocity);
    if (!(closing < Num{})) return Num{};
    ball.velocity = ball.velocity - closing * n;
    return -closing * ball.mass;
  }

  // The side of a pinch (pinch.hpp) that contact c's partner of ball m makes.
  PinchSide<Num> pinch_side(const World<Num>& world, const PersistentContact<Num>& c, int m) const {
    if (!c.with_wall()) {
      const Body<Num>& s = world.balls[c.partner_of(m)];
      return {false, s.position, {}, s.radius};
    }
    const WallGeometry<Num>& w = world.walls[c.wall];
    if (c.feature == ContactFeature::wall_face) return {true, w.segment.a, w.unit_normal, Num{}};
    return {false, c.feature == ContactFeature::wall_end_a ? w.segment.a : w.segment.b, {}, Num{}};
  }

  // The other side of a pinch or a wedge of ball m (a wall's feature or a
  // static ball) and the direction its answer takes: a pinch's axis (from
  // the struck side), or a wedge's other normal, each pointing towards m.
  struct Pinch {
    Vec2<Num> axis;
    int wall = -1, ball = -1;
    ContactFeature feature = ContactFeature::ball;
    bool opposite = false;  // a wedge whose normals are opposite to within 2^-15 rad (find_wedge)
  };

  // Each immovable partner that ball m touches (within δ), other than
  // contact c's: f(side, offset from it to m, {wall or ball, feature}).
  template <class F>
  void for_each_other_side(const World<Num>& world, const CellGrid<Num>& grid, const PersistentContact<Num>& c, int m,
                           F f) const {
    const Body<Num>& b = world.balls[m];
    const Num reach = b.radius + th_.band;
    for (int k : grid.walls_near(m)) {
      if (c.with_wall() && k == c.wall) continue;
      const WallGeometry<Num>& w = world.walls[k];
      ContactFeature feature{};
      const Vec2<Num> q = nearest_point(w, b.position, &feature);
      if (reach * reach < length_squared(b.position - q)) continue;
      const bool face = feature == ContactFeature::wall_face;
      f(PinchSide<Num>{face, face ? w.segment.a : q, w.unit_normal, Num{}}, b.position - q, Pinch{{}, k, -1, feature});
    }
    grid.for_each_neighbour(m, [&](int j) {
      const Body<Num>& s = world.balls[j];
      if (j == m || j == c.partner_of(m) || !s.is_static() || !within_band(b, s)) return;
      f(PinchSide<Num>{false, s.position, {}, s.radius}, b.position - s.position, Pinch{{}, -1, j, ContactFeature::ball});
    });
  }

  // Among sides equally good, the first wall, then the first ball, by index
  // (not the grid's order, which a resumed run rebuilds differently).
  static bool first_by_index(const Pinch& s1, const Pinch& s2) {
    const bool wall1 = s1.ball < 0, wall2 = s2.ball < 0;
    if (wall1 != wall2) return wall1;
    return wall1 ? s1.wall < s2.wall : s1.ball < s2.ball;
  }

  // The pinch between the partner of contact c and another immovable
  // partner that ball m touches (within δ) on the opposite side, if any:
  // n·n' < −1 + 2δ/r (n, n' the two normals towards m), the largest angle α
  // (1 + n·n' ≈ α²/2) at which a ball of radius r meets the two sides of a
  // pinch narrower than its diameter by δ.
  std::optional<Pinch> find_pinch(const World<Num>& world, const CellGrid<Num>& grid,
                                  const PersistentContact<Num>& c, int m, const Vec2<Num>& n) const {
    const Body<Num>& b = world.balls[m];
    const PinchSide<Num> struck = pinch_side(world, c, m);
    const Num diameter = b.radius + b.radius;
    const Num opposite = num<Num>(2.0) * th_.band / b.radius - Num{1};
    // The most opposite side that makes a pinch.
    std::optional<Pinch> pinch;
    Num most{};
    for_each_other_side(world, grid, c, m, [&](const PinchSide<Num>& other, const Vec2<Num>& offset, Pinch side) {
      if (length_squared(offset) == Num{}) return;  // the centre on the partner: no normal
      const Num d = dot(n, normalized(offset));
      if (!(d < opposite)) return;
      if (pinch && !(d < most || (d == most && first_by_index(side, *pinch)))) return;
      if (const auto axis = pinch_axis(struck, other, diameter)) {
        side.axis = dot(*axis, n) < Num{} ? -*axis : *axis;
        pinch = side;
        most = d;
      }
    });
    return pinch;
  }

  // The other side of a wedge that ball m, struck again on contact c (normal
  // n towards m), is caught in: the first fixed ball or wall feature it
  // touches (within δ) with which the series of strikes at this instant
  // collapses, its normal n2 towards m in `axis` (n, for `opposite`). With
  // c = n·n2 = −cos α:
  // - sides at most a right angle apart (c ≥ 0) end the series within two
  //   strikes, and are not tried;
  // - sides opposite to within α ≤ 2^-15 (1 − c² ≤ 2^-30) are returned
  //   marked `opposite`: the island's complementarity problem cannot tell
  //   two such normals apart (it takes the second for redundant and the ball
  //   sinks into the first), so the engine answers them as a pinch, along
  //   the struck normal; the gap is then narrower than the ball by at most
  //   2^-31 of the sum of the radii (α² = 2δ'/(R + r) against a ball),
  //   far inside the contact band;
  // - the series' two-strike map has complex eigenvalues where
  //   (1 + e)² sin² α > (1 − e)²: it then always turns the ball back (after
  //   ever more strikes as e → 1), so no collapse is declared and the engine
  //   takes the strikes one by one;
  // - below that it collapses unless the ball's velocity turns it back in
  //   the first few strikes: ring_collapses runs the series for 2^10.
  // Sleeping balls are no side here: a strike on a sleeper may wake it,
  // which the engine's own strikes decide.
  std::optional<Pinch> find_wedge(const World<Num>& world, const CellGrid<Num>& grid, const PersistentContact<Num>& c,
                                  int m, const Vec2<Num>& n, const Num& restitution) const {
    const Num zero{}, one{1};
    const Body<Num>& b = world.balls[m];
    std::optional<Pinch> wedge;
    for_each_other_side(world, grid, c, m, [&](const PinchSide<Num>&, const Vec2<Num>& offset, Pinch side) {
      if (length_squared(offset) == zero) return;
      if (side.ball >= 0 && !world.balls[side.ball].fixed) return;
      if (wedge && !first_by_index(side, *wedge)) return;
      const Vec2<Num> n2 = normalized(offset);
      const Num cosine = dot(n, n2);
      if (!(cosine < zero)) return;
      const Num sine_squared = one - cosine * cosine;
      const Num e2 = contact_restitution(b.restitution, side.ball >= 0 ? world.balls[side.ball].restitution
                                                                          : world.wall_restitution[side.wall]);
      const Num e = e2 < restitution ? restitution : e2;  // the livelier side: a collapse found is one for both
      if (!(num<Num>(0x1p-30) < sine_squared)) {
        side.axis = n;
        side.opposite = true;
        wedge = side;
        return;
      }
      side.axis = n2;
      if ((one - e) * (one - e) < (one + e) * (one + e) * sine_squared) return;  // the series always ends
      if (ring_collapses(b.velocity, n, n2, e, 1 << 10)) wedge = side;
    });
    return wedge;
  }

  // The wedge's other side joins the graph (unless ball m holds it
  // already), so that one plastic impact answers both sides.
  void hold_other_side(const World<Num>& world, ContactGraph<Num>& graph, int m, const Pinch& w) const {
    if (w.ball >= 0 ? graph.find_pair(m, w.ball) != nullptr : graph.with_wall(m, w.wall) != nullptr) return;
    Event<Num> side;  // the contact a strike on that side would make
    if (w.ball >= 0) {
      side.kind = EventKind::ball_ball;
      side.a = m < w.ball ? m : w.ball;
      side.b = m < w.ball ? w.ball : m;
    } else {
      side.kind = EventKind::ball_wall;
      side.a = m;
      side.b = w.wall;
    }
    side.feature = w.feature;
    graph.add(contact_for(world, side, side.a == m ? w.axis : -w.axis));
  }

  // A held contact with a round partner (a ball, a wall's end) keeps the
  // normal it was made with while the offset slides along its tangent, up
  // to sqrt(2 h_rest / R) rad off the line of centres; but a frictionless
  // round contact pushes along the line of centres. Before a strike's
  // impulses, each round contact of the island is turned onto the present
  // line of centres, n = p / |p| (p the offset from the partner's centre),
  // and goes on along the tangent there, ±L from the tangent point R n:
  // what the strike passes to a support then lies along the support's
  // normal. (Seed 777 of wake-keeps-momentum: a strike of 3.72 on a ball
  // held 1.87e-4 rad off its support's line of centres moved 7.0e-4 of
  // momentum outside the supports' cone.) A pinch's far side keeps the axis
  // it was turned onto; its struck contact with a round partner is turned
  // back onto the line of centres after the pinch's impact (collide).
  void align_round_contacts(const World<Num>& world, ContactGraph<Num>& graph, std::span<const int> island) const {
    for (int x : island)
      graph.for_each_contact_of(x, [&](const PersistentContact<Num>& held) {
        if (held.feature == ContactFeature::wall_face) return;
        if (!held.with_wall() && held.i != x && !world.balls[held.i].is_static()) return;  // met from its ball i
        turn_onto_line_of_centres(world, graph, held);
      });
  }
  // One round contact turned onto the present line of centres (above).
  void turn_onto_line_of_centres(const World<Num>& world, ContactGraph<Num>& graph,
                                 const PersistentContact<Num>& held) const {
    const RoundPartner round = round_partner(world, held);
    const Vec2<Num> p = world.balls[held.i].position - round.centre;
    const Num d2 = length_squared(p);
    if (!(Num{} < d2)) return;
    PersistentContact<Num> turned = held;
    const Num d = NumberTraits<Num>::sqrt(d2);
    along_tangent_at(turned, Vec2<Num>{p.x / d, p.y / d}, world, round);
    graph.reshape(turned);
  }

  static void align_other_side(ContactGraph<Num>& graph, int m, const Pinch& p) {
    const PersistentContact<Num>* held = p.ball >= 0 ? graph.find_pair(m, p.ball) : graph.with_wall(m, p.wall);
    if (held == nullptr || held->feature != p.feature) return;
    PersistentContact<Num> aligned = *held;
    aligned.normal = aligned.i == m ? -p.axis : p.axis;  // from the other side towards m, as a contact's normal points towards i
    graph.reshape(aligned);  // the same contact turned, not one that ended (ContactGraph::parted)
  }

  // A jammed strike (rule 1) is one of a series at a single instant: the
  // struck balls touch other balls of their island (within the contact band
  // δ) that they are not held to, and the pairwise answers would pass the
  // momentum back and forth between them, a factor e smaller each round,
  // for ever (a ball wedged between two neighbours as a pile slides). The
  // series' limit is one simultaneous impact: the pairs of a ball struck at
  // this instant with a touching ball of its island join the graph as
  // ordinary contacts, and one plastic impact of the island (each contact
  // pushing where it closes; where it parts, let go, or held if it parts
  // slower than v_rest, as every contact of an impact) leaves none of them
  // closing. Every ball of the island struck at this instant is asked, not
  // only the pair struck now: two pairs of one island, each made plastic
  // and then let go by the forces (accelerated apart), each left the other
  // closing by 1e-9 m/s, for ever (a held-out pile of 50 equal balls
  // sliding as one crystal, t = 3.27). Only balls of the island (carried to
  // the present by the caller) are looked at: a touching neighbour outside
  // it is answered by the next strike, itself a jam.
  void join_touching(const World<Num>& world, ContactGraph<Num>& graph, const std::vector<int>& island,
                     const Num& now) const {
    for (int x : island) {
      if (!(world.balls[x].struck_at == now)) continue;  // island balls move: none is static
      for (int y : island) {
        if (y == x || graph.touching(x, y)) continue;
        Event<Num> pair;  // the contact a collision of the two would make (i < j)
        pair.kind = EventKind::ball_ball;
        pair.a = x < y ? x : y;
        pair.b = x < y ? y : x;
        const Body<Num>& a = world.balls[pair.a];
        const Body<Num>& b = world.balls[pair.b];
        const Vec2<Num> offset = a.position - b.position;
        const Num reach = a.radius + b.radius + th_.band;
        if (!(length_squared(offset) < reach * reach)) continue;
        graph.add(contact_for(world, pair, normalized(offset)));
      }
    }
  }

  // The motion of `balls` changed: they join `changed` (to be predicted
  // again) and moved_balls().
  void moved(const std::vector<int>& balls, std::vector<int>& changed) {
    moved_.assign(balls.begin(), balls.end());
    changed.insert(changed.end(), balls.begin(), balls.end());
  }

  RestThresholds<Num> th_;
  Num sqrt_height_;
  Num jam_speed_;  // a jammed or held pair parting slower stays (rule 1): v_rest, or without gravity the creep speed
  Collision<Num> collision_;  // collide()'s answer, its vectors reused
  std::vector<int> moved_;    // moved_balls()
};

}  // namespace collide2d
