// What happens at a contact: the response (reflection, the n–t impulse, a
// held face) and the rest rules of rest.hpp (rest on a face, the sleep
// test, plastic pairs, creep). The engine (event_engine.hpp) decides *when*;
// this decides *what*, and counts what each rule did and the energy it took.
#pragma once

#include <vector>

#include "response/response.hpp"
#include "sim/cell_grid.hpp"
#include "sim/event_queue.hpp"
#include "sim/held_contact.hpp"
#include "sim/rest.hpp"
#include "sim/world.hpp"

namespace collide2d {

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
      : th_(th), sqrt_height_(NumberTraits<Num>::sqrt(th.height)) {}

  const RestThresholds<Num>& thresholds() const { return th_; }
  RestCounters counters;
  Num energy_removed{};  // kinetic energy taken by rest on a face, plastic pairs and sleep
  bool plastic = false;  // the last collide_balls made its pair plastic (rule 4)

  // sqrt(2 g_n h_rest): the speed that rises h_rest against g_n. Formed as
  // sqrt(2 g_n) sqrt(h_rest) so that fixed point cannot round a tiny product
  // to zero.
  Num hop_speed(const Num& g_n) const { return NumberTraits<Num>::sqrt(num<Num>(2.0) * g_n) * sqrt_height_; }

  // Rule 3: a strike this fast wakes a sleeping ball.
  bool wakes(const Num& closing) const { return !(closing < th_.speed); }

  // Rule 5 (creep): a contact nothing presses together (n·Δa ≥ 0), closing
  // slower than the creep speed, is not processed: in a row of balls jammed
  // between walls every impulse would at once cause another at the same
  // instant, without end. The pair is predicted again when either ball's
  // motion next changes.
  bool creeping(const Vec2<Num>& n, const Vec2<Num>& relative_velocity, const Vec2<Num>& relative_acceleration) {
    if (dot(n, relative_acceleration) < Num{} || !(-dot(n, relative_velocity) < th_.creep_speed)) return false;
    ++counters.creeping;
    return true;
  }

  // Rule 2: slower than v_rest and carried by its static supports.
  bool can_sleep(const World<Num>& world, const CellGrid<Num>& grid, int i) const {
    const Body<Num>& b = world.balls[i];
    if (b.is_static() || !(length_squared(b.velocity) < th_.speed * th_.speed)) return false;
    if (b.free_acceleration.x == Num{} && b.free_acceleration.y == Num{}) return false;  // no weight to carry
    return carried(world, grid, i);
  }

  // The load on ball i, −(its free acceleration plus the pushes of the
  // moving balls it is in contact with: contact_graph.hpp), lies in the cone
  // of the normals of the walls and static balls within the contact band
  // (rest.hpp, rule 2). Its acceleration holds those pushes, and on a face
  // the face's own reaction, which is taken out.
  bool carried(const World<Num>& world, const CellGrid<Num>& grid, int i) const {
    const Body<Num>& b = world.balls[i];
    const Vec2<Num> load = b.asleep ? b.free_acceleration : b.acceleration + (b.free_acceleration - own_acceleration(b));
    std::vector<Vec2<Num>> normals;
    for (const WallGeometry<Num>& w : world.walls) {
      const Vec2<Num> q = nearest_point(w, b.position);
      const Num reach = b.radius + th_.band;
      if (!(reach * reach < length_squared(b.position - q))) normals.push_back(normalized(b.position - q));
    }
    grid.for_each_neighbour(i, [&](int j) {
      const Body<Num>& s = world.balls[j];
      if (j == i || !s.is_static()) return;
      const Num reach = b.radius + s.radius + th_.band;
      if (!(reach * reach < length_squared(b.position - s.position))) normals.push_back(normalized(b.position - s.position));
    });
    return carried_by(load, normals);
  }

  void put_to_sleep(Body<Num>& b) {
    energy_removed = energy_removed + kinetic_energy(b);
    b.velocity = {};
    b.acceleration = {};
    b.on_face = false;
    b.asleep = true;
    ++counters.fell_asleep;
  }

  static void wake(Body<Num>& b) {
    b.asleep = false;
    b.acceleration = b.free_acceleration;
  }

  // Leaving its face: a struck ball moves freely again. Only the face's
  // part of its acceleration goes; contact forces (contact_graph.hpp) stay
  // until its island is solved again.
  static void free(Body<Num>& b) {
    if (b.asleep || !b.on_face) return;
    const Vec2<Num> on_face = own_acceleration(b);
    b.on_face = false;
    b.acceleration = b.acceleration + (b.free_acceleration - on_face);
  }

  // Ball a meets ball b (n from b to a). A sleeping ball here was not woken:
  // it is as immovable as a fixed one.
  Collision<Num> collide_balls(World<Num>& world, const Event<Num>& e) {
    const Num zero{};
    plastic = false;
    Body<Num>& a = world.balls[e.a];
    Body<Num>& b = world.balls[e.b];
    const Vec2<Num> n = normalized(a.position - b.position);  // from b to a
    const Num restitution = contact_restitution(a.restitution, b.restitution);
    // A ball resting on a face that this contact pushes into it: both
    // contacts act at once (held_contact.hpp).
    bool a_held = pushed_into_its_face(a, n), b_held = pushed_into_its_face(b, -n);
    if ((a.on_face && !a_held) || (b.on_face && !b_held)) {
      // A resting ball the contact lifts off its face slower than the hop
      // speed stays held: the lift from the free impulse.
      const Num closing = dot(n, a.velocity - b.velocity);
      if (closing < zero) {
        const Num inv_a = a.is_static() ? zero : num<Num>(1.0) / a.mass, inv_b = b.is_static() ? zero : num<Num>(1.0) / b.mass;
        const Num J = -(num<Num>(1.0) + restitution) * closing / (inv_a + inv_b);
        auto low_lift = [&](const Body<Num>& x, const Vec2<Num>& n_x, const Num& inv) {
          const Num g_n = -dot(x.free_acceleration, x.face.normal);
          return zero < g_n && lifted_less_than(x, n_x, J * inv, hop_speed(g_n));
        };
        if (a.on_face && !a_held) a_held = low_lift(a, n, inv_a);
        if (b.on_face && !b_held) b_held = low_lift(b, -n, inv_b);
      }
    }
    if ((a_held || b_held) && (a.is_static() || b.is_static())) {
      ++counters.held;
      const Num impulse = collide_held(a, b, a_held, b_held, n, restitution);
      changed(a), changed(b);
      return {e.time, EventKind::ball_ball, e.a, e.b, impulse};
    }
    Num impulse{};
    if (a.is_static() || b.is_static()) {
      Body<Num>& mover = b.is_static() ? a : b;
      const Vec2<Num> normal = b.is_static() ? n : -n;
      const Vec2<Num> before = mover.velocity;
      free(mover);
      mover.velocity = reflect_velocity(before, normal, restitution);
      const int obstacle = b.is_static() ? e.b : e.a;
      rest_on_face_if_low(mover, normal, [&] {
        return tangent_face(mover.position, normal, a.radius + b.radius, th_.height, -1, obstacle, ContactFeature::ball);
      });
      impulse = mover.mass * dot(mover.velocity - before, normal);
    } else {
      if (a_held || b_held) {
        ++counters.held;
        impulse = collide_held(a, b, a_held, b_held, n, restitution);
      } else {
        const TwoBallVelocities<Num> out = two_ball_impulse_response(a.velocity, b.velocity, a.mass, b.mass, n, restitution);
        a.velocity = out.v1;
        b.velocity = out.v2;
        impulse = out.impulse;
      }
      if (!a_held) free(a);
      if (!b_held) free(b);
      impulse = impulse + plastic_if_low(world, e, n, a_held, b_held);
    }
    changed(a), changed(b);
    return {e.time, EventKind::ball_ball, e.a, e.b, impulse};
  }

  // Ball a meets wall e.b; n is the wall's unit normal at the contact,
  // towards the ball.
  Collision<Num> collide_with_wall(World<Num>& world, const Event<Num>& e, const Vec2<Num>& n) {
    Body<Num>& a = world.balls[e.a];
    const WallGeometry<Num>& w = world.walls[e.b];
    const Num restitution = contact_restitution(a.restitution, world.wall_restitution[e.b]);
    changed(a);
    // Resting on a face that this wall pushes it into (a wedge): held, like a
    // ball struck into its face (held_contact.hpp).
    if (pushed_into_its_face(a, n)) {
      ++counters.held;
      const Num impulse = bounce_along_face(a, dot(n, a.face.tangent), restitution);
      return {e.time, EventKind::ball_wall, e.a, e.b, impulse};
    }
    const Vec2<Num> before = a.velocity;
    free(a);
    a.velocity = reflect_velocity(before, n, restitution);
    // On the face, between its ends, the ball rests on the wall's face;
    // anywhere else (an end, or a face contact past an end) on the tangent
    // at the end.
    const Num along = dot(w.direction.hi, a.position - w.segment.a);
    const bool on_face = e.feature == ContactFeature::wall_face && Num{} < along && along < w.length_squared;
    const ContactFeature end = along < NumberTraits<Num>::half(w.length_squared) ? ContactFeature::wall_end_a : ContactFeature::wall_end_b;
    rest_on_face_if_low(a, n, [&] {
      return on_face ? face_of_wall(a, w, n, e.b) : tangent_face(a.position, n, a.radius, th_.height, e.b, -1, end);
    });
    const Num impulse = a.mass * dot(a.velocity - before, n);
    return {e.time, EventKind::ball_wall, e.a, e.b, impulse};
  }

 private:
  RestThresholds<Num> th_;
  Num sqrt_height_;

  // A new motion: predictions made with the old one are stale. A static
  // ball's motion never changes, so its pending predictions stay valid.
  static void changed(Body<Num>& b) {
    if (!b.is_static()) ++b.version;
  }

  // Rule 1: ball x (free of any face) has just rebounded off something that
  // cannot move (unit normal n towards x). Pressed against it (g_n > 0, by
  // its weight and the pushes of its contacts: its acceleration) and rising
  // less than h_rest, it loses its normal speed and slides along `make_face()`.
  template <class MakeFace>
  void rest_on_face_if_low(Body<Num>& x, const Vec2<Num>& n, MakeFace make_face) {
    const Num zero{};
    const Num pressing = -dot(x.acceleration, n);  // g_n
    const Num rebound = dot(x.velocity, n);
    if (!(zero < pressing) || !(rebound < hop_speed(pressing))) return;
    energy_removed = energy_removed + x.mass * NumberTraits<Num>::half(rebound * rebound);
    x.velocity = x.velocity - rebound * n;
    x.acceleration = x.acceleration + pressing * n;  // the tangential part
    x.on_face = true;
    x.face = make_face();
    ++counters.came_to_rest;
  }

  // The face of wall w (normal n towards x): the centre stays on it while its
  // projection lies between the wall's ends.
  static Face<Num> face_of_wall(const Body<Num>& x, const WallGeometry<Num>& wall, const Vec2<Num>& n, int w) {
    Face<Num> f;
    f.normal = n;
    f.tangent = tangent_of(n);
    f.origin = x.position;
    const Num at_a = dot(f.tangent, wall.segment.a - x.position), at_b = dot(f.tangent, wall.segment.b - x.position);
    f.lo = at_a < at_b ? at_a : at_b;
    f.hi = at_a < at_b ? at_b : at_a;
    f.wall = w;
    f.feature = ContactFeature::wall_face;
    return f;
  }

  // Rule 4 (rest.hpp): balls e.a and e.b (moving; n from b to a; `*_held`
  // on their faces) have just collided. Pressed together (n·Δa < 0) and
  // parting slower than the hop speed (a rise below h_rest), they part not
  // at all: an impulse takes their normal separating speed to zero, and
  // `plastic` is set so that the engine keeps it there (contact_graph.hpp).
  // Returns the impulse on a.
  Num plastic_if_low(World<Num>& world, const Event<Num>& e, const Vec2<Num>& n, bool a_held, bool b_held) {
    const Num zero{};
    Body<Num>& a = world.balls[e.a];
    Body<Num>& b = world.balls[e.b];
    const Num pressing = dot(n, a.acceleration - b.acceleration);
    if (!(pressing < zero)) return zero;
    Mobility<Num> ma(a, n, a_held), mb(b, -n, b_held);
    const Num k = ma.inverse_mass() + mb.inverse_mass();
    const Num parting = ma.speed_along_n() + mb.speed_along_n();
    if (k == zero || !(parting < hop_speed(-pressing))) return zero;
    const Num before = kinetic_energy(a) + kinetic_energy(b);
    const Num J = -parting / k;
    ma.apply(J);
    mb.apply(J);
    plastic = true;
    energy_removed = energy_removed + (before - kinetic_energy(a) - kinetic_energy(b));
    ++counters.plastic_pairs;
    return J;
  }
};

}  // namespace collide2d
