// Persistent (plastic) contacts between moving balls, and the constant
// forces that keep them (rest.hpp, rule 4).
//
// A contact c between balls i and j (unit normal n_c from j towards i) holds
// their relative motion to the tangent at the contact: the relative normal
// acceleration n_c·(a_i − a_j) is zero. Each ball x answers a force f with
// the acceleration W_x f: W = I/m free, t tᵀ/m held on a face (unit tangent
// t), 0 static. The contacts that touch one another through shared balls
// form an island; its forces λ ≥ 0 solve
//     Σ_d A_cd λ_d = −b_c,   A_cd = Σ_{x ∈ c∩d} n_c^x · W_x n_d^x,
//                            b_c  = Σ_{x ∈ c} n_c^x · a_x,
// where n_c^x is n_c pointing towards x and a_x the ball's own acceleration
// (own_acceleration in world.hpp). A contact whose λ comes out negative is
// pulling, not pushing: it is dropped (the pair separates by itself) and the
// island solved again. Contacts are solved in (i, j) order, so the forces do
// not depend on the order in which contacts were made.
//
// When a contact joins an island at an impact, the island first takes the
// impulses P that stop every contact's relative normal velocity: the same
// equations with b_c = n_c·(v_i − v_j), a plastic impact of the whole
// island. A contact already parting at the rest speed or faster is no
// longer plastic and leaves first (rest.hpp: it would rise more than
// h_rest); the others are held at zero whatever the sign of P (a slower
// parting is a bounce too low to count, as on a face). Kinetic energy can
// only fall: the impulses project the velocities onto the contacts'
// tangents in the metric of the inverse masses.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "sim/state_bytes.hpp"
#include "sim/world.hpp"

namespace collide2d {

template <class Num>
struct PersistentContact {
  int i = 0, j = 0;  // balls, i < j
  Vec2<Num> normal;  // unit, from j towards i
  Vec2<Num> origin;  // p_i − p_j when it began: the tangent passes through it
  Num L{};           // it ends when p_i − p_j has slid L along the tangent
};

template <class Num>
class ContactGraph {
 public:
  void reset(std::size_t balls) {
    contacts_.clear();
    of_ball_.assign(balls, {});
  }
  const std::vector<PersistentContact<Num>>& contacts() const { return contacts_; }

  bool touching(int a, int b) const {
    for (int c : of_ball_[a])
      if (other(contacts_[c], a) == b) return true;
    return false;
  }
  bool in_contact(int a) const { return !of_ball_[a].empty(); }

  // The contacts of ball a, as (partner, contact) for predictions.
  template <class Visit>
  void for_each_contact_of(int a, Visit visit) const {
    for (int c : of_ball_[a]) visit(contacts_[c]);
  }

  void add(const PersistentContact<Num>& c) {
    contacts_.push_back(c);
    rebuild();
  }

  // Removes every contact of ball a; returns its former partners.
  std::vector<int> remove_all_of(int a) {
    std::vector<int> partners;
    for (int c : of_ball_[a]) partners.push_back(other(contacts_[c], a));
    if (partners.empty()) return partners;
    contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(), [&](const PersistentContact<Num>& c) {
                      return c.i == a || c.j == a;
                    }),
                    contacts_.end());
    rebuild();
    return partners;
  }
  void remove(int a, int b) {
    contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(), [&](const PersistentContact<Num>& c) {
                      return (c.i == a && c.j == b) || (c.i == b && c.j == a);
                    }),
                    contacts_.end());
    rebuild();
  }

  // The balls connected to `seeds` through contacts (the seeds too), sorted.
  std::vector<int> island(const std::vector<int>& seeds) const {
    std::vector<char> seen(of_ball_.size(), 0);
    std::vector<int> out, stack(seeds.begin(), seeds.end());
    while (!stack.empty()) {
      const int x = stack.back();
      stack.pop_back();
      if (seen[x]) continue;
      seen[x] = 1;
      out.push_back(x);
      for (int c : of_ball_[x]) stack.push_back(other(contacts_[c], x));
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  // Every ball of `balls` (an island, carried to the present by the caller)
  // takes the impulses that stop its contacts' normal velocities, if
  // `impact` (contacts parting at `parting_speed` or faster leave first),
  // then its own acceleration plus the contact forces. Contacts that would
  // pull are dropped.
  void solve(World<Num>& world, const std::vector<int>& balls, bool impact, const Num& parting_speed) {
    if (impact) {
      for (int c = static_cast<int>(contacts_.size()) - 1; c >= 0; --c) {
        const PersistentContact<Num>& k = contacts_[c];
        if (std::binary_search(balls.begin(), balls.end(), k.i) &&
            !(dot(k.normal, world.balls[k.i].velocity - world.balls[k.j].velocity) < parting_speed))
          remove(k.i, k.j);
      }
      std::vector<Num> P;
      const std::vector<int> ids = solve_active(world, balls, P, [&](const Body<Num>& x) { return x.velocity; }, false);
      for (std::size_t k = 0; k < ids.size(); ++k) {
        const PersistentContact<Num>& c = contacts_[ids[k]];
        world.balls[c.i].velocity = world.balls[c.i].velocity + mobility(world.balls[c.i], P[k] * c.normal);
        world.balls[c.j].velocity = world.balls[c.j].velocity - mobility(world.balls[c.j], P[k] * c.normal);
      }
    }
    std::vector<Num> lambda;
    const std::vector<int> ids = solve_active(world, balls, lambda, [](const Body<Num>& x) { return own_acceleration(x); }, true);
    for (int x : balls) world.balls[x].acceleration = own_acceleration(world.balls[x]);
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const PersistentContact<Num>& c = contacts_[ids[k]];
      world.balls[c.i].acceleration = world.balls[c.i].acceleration + mobility(world.balls[c.i], lambda[k] * c.normal);
      world.balls[c.j].acceleration = world.balls[c.j].acceleration - mobility(world.balls[c.j], lambda[k] * c.normal);
    }
  }

  void save(ByteWriter& out) const {
    out.put(static_cast<std::uint64_t>(contacts_.size()));
    for (const PersistentContact<Num>& c : contacts_) {
      out.put(static_cast<std::int32_t>(c.i));
      out.put(static_cast<std::int32_t>(c.j));
      out.put(c.normal);
      out.put(c.origin);
      out.put(c.L);
    }
  }
  void load(ByteReader& in) {
    std::uint64_t n = 0;
    in.get(n);
    contacts_.assign(n, {});
    for (PersistentContact<Num>& c : contacts_) {
      std::int32_t i = 0, j = 0;
      in.get(i);
      in.get(j);
      c.i = i, c.j = j;
      in.get(c.normal);
      in.get(c.origin);
      in.get(c.L);
    }
    rebuild();
  }

 private:
  std::vector<PersistentContact<Num>> contacts_;  // sorted by (i, j)
  std::vector<std::vector<int>> of_ball_;

  static int other(const PersistentContact<Num>& c, int a) { return c.i == a ? c.j : c.i; }

  void rebuild() {
    std::sort(contacts_.begin(), contacts_.end(),
              [](const PersistentContact<Num>& x, const PersistentContact<Num>& y) { return x.i != y.i ? x.i < y.i : x.j < y.j; });
    for (auto& list : of_ball_) list.clear();
    for (int c = 0; c < static_cast<int>(contacts_.size()); ++c) {
      of_ball_[contacts_[c].i].push_back(c);
      of_ball_[contacts_[c].j].push_back(c);
    }
  }

  // W_x f: how ball x accelerates under force f.
  static Vec2<Num> mobility(const Body<Num>& x, const Vec2<Num>& f) {
    if (x.is_static()) return {};
    if (x.on_face) return (dot(f, x.face.tangent) / x.mass) * x.face.tangent;
    return (num<Num>(1.0) / x.mass) * f;
  }
  // The island's contacts and their x for A x = −b with b_c =
  // n_c·(q(i) − q(j)), q a ball's velocity or own acceleration; with
  // `non_negative`, contacts that would need x < 0 are dropped until none
  // does. Returns the contacts' indices, x in `x`.
  template <class Quantity>
  std::vector<int> solve_active(const World<Num>& world, const std::vector<int>& balls, std::vector<Num>& x, Quantity q,
                                bool non_negative) {
    for (;;) {
      std::vector<int> ids;  // in (i, j) order: contacts_ is kept sorted
      for (int c = 0; c < static_cast<int>(contacts_.size()); ++c)
        if (std::binary_search(balls.begin(), balls.end(), contacts_[c].i)) ids.push_back(c);
      int worst = -1;
      if (solve_linear(world, ids, x, worst, q, non_negative)) return ids;
      remove(contacts_[ids[worst]].i, contacts_[ids[worst]].j);
    }
  }

  // Solves A x = −b (see the top) by Gaussian elimination with partial
  // pivoting. False, with `worst` set, when a contact must go: a zero pivot
  // (it adds nothing the others do not: a ball that cannot move along it),
  // or the most negative x.
  template <class Quantity>
  bool solve_linear(const World<Num>& world, const std::vector<int>& ids, std::vector<Num>& lambda, int& worst,
                    Quantity q, bool non_negative) const {
    const Num zero{};
    const std::size_t k = ids.size();
    std::vector<std::vector<Num>> A(k, std::vector<Num>(k + 1, zero));
    for (std::size_t r = 0; r < k; ++r) {
      const PersistentContact<Num>& c = contacts_[ids[r]];
      const Body<Num>& bi = world.balls[c.i];
      const Body<Num>& bj = world.balls[c.j];
      A[r][k] = -(dot(c.normal, q(bi)) - dot(c.normal, q(bj)));
      for (std::size_t s = 0; s < k; ++s) {
        const PersistentContact<Num>& d = contacts_[ids[s]];
        Num sum = zero;
        for (int x : {c.i, c.j}) {
          if (x != d.i && x != d.j) continue;
          const Vec2<Num> nc = x == c.i ? c.normal : -c.normal;
          const Vec2<Num> nd = x == d.i ? d.normal : -d.normal;
          sum = sum + dot(nc, mobility(world.balls[x], nd));
        }
        A[r][s] = sum;
      }
    }
    std::vector<std::size_t> row(k);
    for (std::size_t r = 0; r < k; ++r) row[r] = r;
    for (std::size_t col = 0; col < k; ++col) {
      std::size_t best = col;
      auto magnitude = [](const Num& x) { return x < Num{} ? -x : x; };
      for (std::size_t r = col + 1; r < k; ++r)
        if (magnitude(A[row[best]][col]) < magnitude(A[row[r]][col])) best = r;
      std::swap(row[col], row[best]);
      const Num pivot = A[row[col]][col];
      if (pivot == zero) {
        worst = static_cast<int>(col);
        return false;
      }
      for (std::size_t r = col + 1; r < k; ++r) {
        const Num f = A[row[r]][col] / pivot;
        if (f == zero) continue;
        for (std::size_t s = col; s <= k; ++s) A[row[r]][s] = A[row[r]][s] - f * A[row[col]][s];
      }
    }
    lambda.assign(k, zero);
    for (std::size_t col = k; col-- > 0;) {
      Num sum = A[row[col]][k];
      for (std::size_t s = col + 1; s < k; ++s) sum = sum - A[row[col]][s] * lambda[s];
      lambda[col] = sum / A[row[col]][col];
    }
    for (std::size_t r = 0; r < k && non_negative; ++r)
      if (lambda[r] < zero && (worst < 0 || lambda[r] < lambda[static_cast<std::size_t>(worst)])) worst = static_cast<int>(r);
    return worst < 0;
  }
};

}  // namespace collide2d
