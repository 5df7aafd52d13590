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
// (own_acceleration in world.hpp), with λ ≥ 0 and, for a contact given no
// force, a relative normal acceleration ≥ 0: a linear complementarity
// problem (solve_island). A contact given no force separates and leaves.
// Contacts are solved in (i, j) order, so the forces do not depend on the
// order in which contacts were made.
//
// When a contact joins an island at an impact, the island first takes the
// impulses P that stop every contact's relative normal velocity: the same
// equations with b_c = n_c·(v_i − v_j), a plastic impact of the whole
// island. A contact whose normal speed is the rest speed or more, parting
// (it would rise more than h_rest: rest.hpp) or closing (a real impact, to
// be met with its restitution), leaves first; the others are held at zero
// whatever the sign of P (slower is a bounce too low to count, as on a
// face). Kinetic energy can
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
  // `impact` (contacts whose normal speed is `rest_speed` or more leave first),
  // then its own acceleration plus the contact forces. Contacts that would
  // pull leave.
  void solve(World<Num>& world, const std::vector<int>& balls, bool impact, const Num& rest_speed) {
    if (impact) {
      for (int c = static_cast<int>(contacts_.size()) - 1; c >= 0; --c) {
        const PersistentContact<Num>& k = contacts_[c];
        const Num v_n = dot(k.normal, world.balls[k.i].velocity - world.balls[k.j].velocity);
        if (std::binary_search(balls.begin(), balls.end(), k.i) && !(v_n < rest_speed && -v_n < rest_speed)) remove(k.i, k.j);
      }
      for (const auto& [c, P] : solve_island(world, balls, [&](const Body<Num>& x) { return x.velocity; }, false)) {
        world.balls[c.i].velocity = world.balls[c.i].velocity + mobility(world.balls[c.i], P * c.normal);
        world.balls[c.j].velocity = world.balls[c.j].velocity - mobility(world.balls[c.j], P * c.normal);
      }
    }
    const auto forces = solve_island(world, balls, [](const Body<Num>& x) { return own_acceleration(x); }, true);
    for (int x : balls) world.balls[x].acceleration = own_acceleration(world.balls[x]);
    for (const auto& [c, lambda] : forces) {
      world.balls[c.i].acceleration = world.balls[c.i].acceleration + mobility(world.balls[c.i], lambda * c.normal);
      world.balls[c.j].acceleration = world.balls[c.j].acceleration - mobility(world.balls[c.j], lambda * c.normal);
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
  // The island's contacts with their x for A x = −b, b_c = n_c·(q(i) − q(j)),
  // q a ball's velocity or own acceleration (see the top). A contact that
  // adds nothing the others do not (a zero pivot: a ball that cannot move
  // along it) leaves. With `complementary`, x ≥ 0 and the contacts'
  // resulting normal accelerations w = A x + b ≥ 0 with x·w = 0: each
  // contact pushes or separates, never pulls nor sinks. That linear
  // complementarity problem is solved exactly by Murty's least-index
  // principal pivoting (A is positive definite, so it ends): the active set
  // starts with every contact; the lowest-numbered contact breaking a sign
  // condition (beyond its inputs' rounding, 2^-40 of their size) flips in or
  // out, until none does. The contacts left out separate and leave.
  template <class Quantity>
  std::vector<std::pair<PersistentContact<Num>, Num>> solve_island(const World<Num>& world, const std::vector<int>& balls,
                                                                   Quantity q, bool complementary) {
    for (;;) {
      std::vector<int> ids;  // in (i, j) order: contacts_ is kept sorted
      for (int c = 0; c < static_cast<int>(contacts_.size()); ++c)
        if (std::binary_search(balls.begin(), balls.end(), contacts_[c].i)) ids.push_back(c);
      const std::size_t k = ids.size();
      std::vector<std::vector<Num>> A;
      std::vector<Num> b, size;
      assemble(world, ids, q, A, b, size);
      std::vector<char> active(k, 1);
      std::vector<Num> x;
      std::size_t singular = k;
      const Num zero{}, rounding = num<Num>(0x1p-40);
      bool solved = false;
      for (std::size_t iteration = 0; iteration < 64 * k + 64 && !solved; ++iteration) {
        if (!solve_subset(A, b, active, x, singular)) break;
        solved = true;
        if (!complementary) break;
        for (std::size_t r = 0; r < k; ++r) {
          Num w = b[r];
          for (std::size_t s = 0; s < k; ++s) w = w + A[r][s] * x[s];
          const Num tolerance = rounding * size[r];
          const bool pulls = active[r] && x[r] * A[r][r] < -tolerance;
          const bool sinks = !active[r] && w < -tolerance;
          if (pulls || sinks) {
            active[r] = !active[r];
            solved = false;
            break;
          }
        }
      }
      if (singular < k) {
        remove(contacts_[ids[singular]].i, contacts_[ids[singular]].j);
        continue;
      }
      std::vector<std::pair<PersistentContact<Num>, Num>> out;
      std::vector<std::pair<int, int>> leaving;
      for (std::size_t r = 0; r < k; ++r) {
        const PersistentContact<Num>& c = contacts_[ids[r]];
        if (!active[r]) leaving.push_back({c.i, c.j});
        else out.push_back({c, complementary && x[r] < zero ? zero : x[r]});
      }
      for (const auto& [i, j] : leaving) remove(i, j);
      return out;
    }
  }

  template <class Quantity>
  void assemble(const World<Num>& world, const std::vector<int>& ids, Quantity q, std::vector<std::vector<Num>>& A,
                std::vector<Num>& b, std::vector<Num>& size) const {
    const Num zero{};
    const std::size_t k = ids.size();
    A.assign(k, std::vector<Num>(k, zero));
    b.assign(k, zero);
    size.assign(k, zero);
    for (std::size_t r = 0; r < k; ++r) {
      const PersistentContact<Num>& c = contacts_[ids[r]];
      const Body<Num>& bi = world.balls[c.i];
      const Body<Num>& bj = world.balls[c.j];
      b[r] = dot(c.normal, q(bi)) - dot(c.normal, q(bj));
      size[r] = NumberTraits<Num>::sqrt(length_squared(q(bi))) + NumberTraits<Num>::sqrt(length_squared(q(bj)));
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
  }

  // x on the active contacts solves A_SS x_S = −b_S (Gaussian elimination
  // with partial pivoting), zero elsewhere. False, with `singular` the
  // contact of a zero pivot, when A_SS is singular.
  static bool solve_subset(const std::vector<std::vector<Num>>& A, const std::vector<Num>& b, const std::vector<char>& active,
                           std::vector<Num>& x, std::size_t& singular) {
    const Num zero{};
    const std::size_t k = b.size();
    std::vector<std::size_t> S;
    for (std::size_t r = 0; r < k; ++r)
      if (active[r]) S.push_back(r);
    const std::size_t m = S.size();
    std::vector<std::vector<Num>> M(m, std::vector<Num>(m + 1, zero));
    for (std::size_t r = 0; r < m; ++r) {
      for (std::size_t s = 0; s < m; ++s) M[r][s] = A[S[r]][S[s]];
      M[r][m] = -b[S[r]];
    }
    std::vector<std::size_t> row(m);
    for (std::size_t r = 0; r < m; ++r) row[r] = r;
    auto magnitude = [](const Num& v) { return v < Num{} ? -v : v; };
    for (std::size_t col = 0; col < m; ++col) {
      std::size_t best = col;
      for (std::size_t r = col + 1; r < m; ++r)
        if (magnitude(M[row[best]][col]) < magnitude(M[row[r]][col])) best = r;
      std::swap(row[col], row[best]);
      const Num pivot = M[row[col]][col];
      if (pivot == zero) {
        singular = S[col];
        return false;
      }
      for (std::size_t r = col + 1; r < m; ++r) {
        const Num f = M[row[r]][col] / pivot;
        if (f == zero) continue;
        for (std::size_t s = col; s <= m; ++s) M[row[r]][s] = M[row[r]][s] - f * M[row[col]][s];
      }
    }
    std::vector<Num> xs(m, zero);
    for (std::size_t col = m; col-- > 0;) {
      Num sum = M[row[col]][m];
      for (std::size_t s = col + 1; s < m; ++s) sum = sum - M[row[col]][s] * xs[s];
      xs[col] = sum / M[row[col]][col];
    }
    x.assign(k, zero);
    for (std::size_t r = 0; r < m; ++r) x[S[r]] = xs[r];
    return true;
  }
};

}  // namespace collide2d
