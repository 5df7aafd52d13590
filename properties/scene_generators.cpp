#include "scene_generators.hpp"

#include <algorithm>
#include <cmath>

#include "collide2d/geometry/segment_distance.hpp"
#include "scene_checks.hpp"
#include "scene_json.hpp"

namespace collide2d::properties {
namespace {

// An integer in [−n, n] that shrinks towards 0.
int centred(int n) {
  const int magnitude = *rc::gen::inRange(0, n + 1);
  return *rc::gen::arbitrary<bool>() ? -magnitude : magnitude;
}
double sixty_fourths(int n) { return centred(n) / 64.0; }

// The same at RapidCheck's nominal size, whatever the case's size: inRange
// narrows its range with the size (to min at size 0), which would leave a
// crowd drawn early in a run standing still. It still shrinks towards 0.
int centred_full(int n) {
  const int magnitude = *rc::gen::resize(100, rc::gen::inRange(0, n + 1));
  return *rc::gen::arbitrary<bool>() ? -magnitude : magnitude;
}

enum Family { random_box, grazing, simultaneous, resting, fast, crowd, cradle, family_count };

BallSpec ball_at(double x, double y, double vx, double vy, double r) {
  BallSpec b;
  b.position = {x, y};
  b.velocity = {vx, vy};
  b.radius = r;
  return b;
}

// Mass 1 + k/4 (k ≥ 0: shrinks to 1), restitution 1 − k/64 ≥ 1/2 (to 1;
// dissipative: k ≥ 1, to 63/64).
void vary_material(BallSpec& b, const SceneOptions& o) {
  b.mass = 1 + *rc::gen::inRange(0, 13) / 4.0;
  b.restitution = o.elastic ? 1.0 : 1 - *rc::gen::inRange(o.dissipative ? 1 : 0, 33) / 64.0;
}

double wall_restitution(const SceneOptions& o) {
  return o.elastic ? 1.0 : 1 - *rc::gen::inRange(o.dissipative ? 1 : 0, 17) / 64.0;
}

void add_box(Scene& s, double x0, double y0, double x1, double y1, const SceneOptions& o, bool floor = true) {
  if (floor) s.walls.push_back({{x0, y0}, {x1, y0}, wall_restitution(o)});
  s.walls.push_back({{x1, y0}, {x1, y1}, wall_restitution(o)});
  s.walls.push_back({{x1, y1}, {x0, y1}, wall_restitution(o)});
  s.walls.push_back({{x0, y1}, {x0, y0}, wall_restitution(o)});
}

bool valid(const Scene& s) {
  try {
    check_no_initial_overlap(s);
    return true;
  } catch (const SceneError&) {
    return false;
  }
}

void maybe_gravity(Scene& s) {
  if (*rc::gen::arbitrary<bool>()) s.gravity = {centred(4) / 4.0, -*rc::gen::inRange(4, 41) / 4.0};
}

// Balls on a grid of 2×2 cells, each within 1/4 of its cell's centre with
// radius ≤ 1/2: centres ≥ 3/2 apart, ≥ 3/4 from the cell borders, so no
// two overlap and none touches a wall along a cell border. Inside a box
// (or an open scene, or the box with a funnel below), plus 0–2 segments
// between grid corners (a scene they overlap is discarded). From 1 to
// 2 + size/8 balls (at most 40), or, for a crowd, from `fewest` to `most`,
// with speeds and radii drawn at the nominal size (centred_full).
Scene random_box_scene(const SceneOptions& o, int size, int fewest = 1, int most = 0) {
  Scene s;
  const bool is_crowd = most > 0;
  const int max_balls = is_crowd ? most : std::clamp(2 + size / 8, 2, 40);
  const int n = *rc::gen::inRange(fewest, max_balls + 1);
  auto speed = [&] { return (is_crowd ? centred_full(256) : centred(256)) / 64.0; };
  // The grid's width from the largest count, not from n: removing the last
  // balls while shrinking leaves the others where they were.
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(max_balls))));
  const int rows = (n + cols - 1) / cols;
  for (int k = 0; k < n; ++k) {
    const int r64 = is_crowd ? *rc::gen::resize(100, rc::gen::inRange(8, 33)) : *rc::gen::inRange(8, 33);
    // One draw per statement: the order of a call's arguments is the
    // compiler's choice (gcc: last first on x86-64, first first on aarch64),
    // and the same seed must give the same scene everywhere. This is the
    // order x86-64 gave, so that the stored counterexamples stay.
    const double vy = speed();
    const double vx = speed();
    const double y = 1 + 2 * (k / cols) + sixty_fourths(16);
    const double x = 1 + 2 * (k % cols) + sixty_fourths(16);
    BallSpec b = ball_at(x, y, vx, vy, r64 / 64.0);
    vary_material(b, o);
    if (*rc::gen::weightedElement<bool>({{4, false}, {1, true}})) {
      b.fixed = true;
      b.velocity = {0, 0};
    }
    s.balls.push_back(b);
  }
  const double W = 2 * cols, H = 2 * rows;
  const int walls = *rc::gen::element(0, 1, 1, 2);  // 0 open, 1 box, 2 box with a funnel below
  if (walls == 1) add_box(s, 0, 0, W, H, o);
  if (walls == 2) {
    add_box(s, 0, 0, W, H, o, false);
    const double mouth = 1;  // wider than any diameter
    s.walls.push_back({{0, 0}, {W / 2 - mouth / 2, -W / 2}, wall_restitution(o)});
    s.walls.push_back({{W, 0}, {W / 2 + mouth / 2, -W / 2}, wall_restitution(o)});
    s.walls.push_back({{-W, -W}, {2 * W, -W}, wall_restitution(o)});
  }
  const int segments = *rc::gen::inRange(0, 3);
  for (int k = 0; k < segments; ++k) {
    const Point a{2.0 * *rc::gen::inRange(0, cols + 1), 2.0 * *rc::gen::inRange(0, rows + 1)};
    const Point b{2.0 * *rc::gen::inRange(0, cols + 1), 2.0 * *rc::gen::inRange(0, rows + 1)};
    RC_PRE(a != b);
    s.walls.push_back({a, b, wall_restitution(o)});
  }
  maybe_gravity(s);
  RC_PRE(valid(s));
  return s;
}

// A ball aimed past a target (a free or fixed ball, or a wall's face or end)
// at the contact distance × (1 ± 2^-k), k up to 52: contact or a near miss
// decided in the last bits. No gravity (a straight path aims exactly).
Scene grazing_scene(const SceneOptions& o) {
  Scene s;
  const double r = *rc::gen::inRange(8, 33) / 64.0;
  const int miss_sign = centred(1);  // one draw per statement (random_box_scene)
  const double miss = miss_sign * std::ldexp(1.0, -*rc::gen::inRange(0, 53));
  const double speed = *rc::gen::inRange(16, 257) / 64.0;
  const int target = *rc::gen::inRange(0, 4);  // 0 free ball, 1 fixed ball, 2 wall face, 3 wall end
  if (target <= 1) {
    BallSpec other = ball_at(0, 0, 0, 0, *rc::gen::inRange(8, 33) / 64.0);
    vary_material(other, o);
    other.fixed = target == 1;
    const double offset = (r + other.radius) * (1 + miss);
    BallSpec b = ball_at(-4, offset, speed, 0, r);
    vary_material(b, o);
    s.balls = {b, other};
  } else {
    // A wall along y = 0 from x = −2 to 2; the ball passes along its face at
    // height r(1 + miss), or past its end a at (−2, 0) at distance r(1 + miss).
    s.walls.push_back({{-2, 0}, {2, 0}, wall_restitution(o)});
    BallSpec b = target == 2 ? ball_at(-4, r * (1 + miss), speed, 0, r) : ball_at(-2 - r * (1 + miss), 4, 0, -speed, r);
    vary_material(b, o);
    s.balls = {b};
  }
  s.duration = 8 / speed;
  s.record_interval = s.duration / 8;
  RC_PRE(valid(s));
  return s;
}

// Three balls in a row, the middle one at rest: the outer two arrive within
// δ = 2^-k of each other (k up to 52; δ = 0 is exact simultaneity); or a ball
// into a box corner along the diagonal, offset by δ.
Scene simultaneous_scene(const SceneOptions& o) {
  Scene s;
  const int delta_sign = centred(1);  // one draw per statement (random_box_scene)
  const double delta = delta_sign * std::ldexp(1.0, -*rc::gen::inRange(0, 53));
  if (*rc::gen::arbitrary<bool>()) {
    add_box(s, 0, 0, 4, 4, o);
    BallSpec b = ball_at(2, 2 + delta, -1, -1, 0.5);
    vary_material(b, o);
    s.balls = {b};
  } else {
    const double r = 0.5;
    BallSpec left = ball_at(-3, 0, 1, 0, r), middle = ball_at(0, 0, 0, 0, r), right = ball_at(3 + delta, 0, -1, 0, r);
    for (BallSpec* b : {&left, &middle, &right}) vary_material(*b, o);
    s.balls = {left, middle, right};
  }
  s.duration = 4;
  s.record_interval = 0.5;
  maybe_gravity(s);
  RC_PRE(valid(s));
  return s;
}

// Balls on a floor under gravity: placed exactly in contact with it (and
// with their neighbours: centres 2r apart) or 2^-k above, sliding slowly.
Scene resting_scene(const SceneOptions& o, int size) {
  Scene s;
  const int n = *rc::gen::inRange(1, std::clamp(2 + size / 20, 2, 12));
  const double r = *rc::gen::inRange(8, 33) / 64.0;
  s.walls.push_back({{-1, 0}, {2 * r * n + 1, 0}, wall_restitution(o)});
  s.gravity = {0, -*rc::gen::inRange(4, 41) / 4.0};
  for (int k = 0; k < n; ++k) {
    const double lift = *rc::gen::arbitrary<bool>() ? 0.0 : std::ldexp(1.0, -*rc::gen::inRange(0, 53));
    BallSpec b = ball_at(r + 2 * r * k, r + lift, sixty_fourths(16), 0, r);
    vary_material(b, o);
    s.balls.push_back(b);
  }
  s.duration = 1;
  s.record_interval = 1.0 / 8;
  RC_PRE(valid(s));
  return s;
}

// Every length and speed of a scene times 2^e, then translated by `offset`.
void transform(Scene& s, int e, Point offset) {
  const double k = std::ldexp(1.0, e);
  auto move = [&](Point& p) { p = {k * p[0] + offset[0], k * p[1] + offset[1]}; };
  for (WallSpec& w : s.walls) move(w.a), move(w.b);
  for (BallSpec& b : s.balls) {
    move(b.position);
    b.velocity = {k * b.velocity[0], k * b.velocity[1]};
    b.radius *= k;
    if (b.acceleration) b.acceleration = Point{k * (*b.acceleration)[0], k * (*b.acceleration)[1]};
  }
  s.gravity = {k * s.gravity[0], k * s.gravity[1]};
}

// A Newton's cradle (gases only, SceneOptions::gas): k balls (2 to 6) of
// radius 1/4 in a row on y = 1, touching each other and the wall x = 0
// exactly, struck by one more coming from the right, inside a box. The
// strike passes along the row at one instant, the last ball meets the wall
// then and is struck again (a jam, rest.hpp rule 1; with restitutions below
// 1 a pinch or a plastic impact): the strikes the engine's plain gas path
// must leave to the general one, among plain ones.
Scene cradle_scene(const SceneOptions& o) {
  Scene s;
  const double r = 0.25;
  const int k = *rc::gen::inRange(2, 7);
  for (int i = 0; i < k; ++i) {
    BallSpec b = ball_at(r + 2 * r * i, 1, 0, 0, r);
    vary_material(b, o);
    s.balls.push_back(b);
  }
  const double gap = *rc::gen::inRange(1, 17) / 16.0;
  const double speed = *rc::gen::inRange(1, 65) / 16.0;
  BallSpec striker = ball_at(2 * r * k + r + gap, 1, -speed, 0, r);
  vary_material(striker, o);
  s.balls.push_back(striker);
  add_box(s, 0, 0, 2 * r * k + 4, 2, o);
  s.duration = 2;
  s.record_interval = 1.0 / 8;
  RC_PRE(valid(s));
  return s;
}

// A crowd: 30 to 30 + 1.7 size balls, at most 200 (reached at CI's
// max_size 100), in the random family's box: the ball–ball collisions,
// islands and rest rules of a many-ball scene, which the random family
// (1 to 2 + size/8 balls) rarely makes: at CI size 39 % of its scenes had
// one ball and 2-5 % ten or more.
constexpr int crowd_fewest = 30;
int crowd_most(int size) { return std::clamp(30 + size * 17 / 10, 30, 200); }

}  // namespace

const char* family_name(int family) {
  static const char* names[] = {"random", "grazing", "simultaneous", "resting", "fast", "crowd", "cradle"};
  return family >= 0 && family < family_count ? names[family] : "?";
}

void showValue(const GeneratedScene& generated, std::ostream& os) { showValue(generated.scene, os); }

void tag_features(const GeneratedScene& g) {
  const Scene& s = g.scene;
  int fixed_balls = 0;
  for (const BallSpec& b : s.balls) fixed_balls += b.fixed ? 1 : 0;
  const std::size_t n = s.balls.size();
  RC_TAG(family_name(g.family), s.gravity != Point{0, 0} ? "gravity" : "no gravity",
         n == 1 ? "1 ball" : n <= 3 ? "2-3 balls" : n <= 9 ? "4-9 balls" : n <= 29 ? "10-29 balls" : "30-200 balls",
         fixed_balls ? "fixed balls" : "no fixed ball", g.transformed ? "scaled/translated" : "as built");
}

rc::Gen<GeneratedScene> valid_scene(SceneOptions o) {
  return rc::gen::exec([o] {
    const int size = *rc::gen::withSize([](int n) { return rc::gen::just(n); });
    // The random family first: shrinking goes towards it.
    int family = o.hard_cases ? *rc::gen::weightedElement<int>({{6, random_box}, {1, grazing}, {1, simultaneous},
                                                                     {1, resting}, {1, fast}, {1, crowd}})
                                    : static_cast<int>(random_box);
    if (o.gas && *rc::gen::weightedElement<bool>({{2, false}, {1, true}})) family = cradle;
    Scene s;
    switch (family) {
      case cradle: s = cradle_scene(o); break;
      case grazing: s = grazing_scene(o); break;
      case simultaneous: s = simultaneous_scene(o); break;
      case resting: s = resting_scene(o, size); break;
      case crowd: s = random_box_scene(o, size, crowd_fewest, crowd_most(size)); break;
      default: s = random_box_scene(o, size); break;
    }
    if (o.gas) {
      s.gravity = {0, 0};
      for (BallSpec& b : s.balls) b.acceleration.reset();
    }
    if (family == random_box || family == crowd) {
      s.duration = (family == crowd ? *rc::gen::resize(100, rc::gen::inRange(1, 5)) : *rc::gen::inRange(1, 5)) / 4.0;
      s.record_interval = 1.0 / 16;
    }
    if (family == fast) {
      // Speeds ×2^k (k up to 20, 2^12 in fixed mode): many wall hits per frame.
      const double k = std::ldexp(1.0, *rc::gen::inRange(4, o.fixed_mode ? 13 : 21));
      for (BallSpec& b : s.balls) b.velocity = {k * b.velocity[0], k * b.velocity[1]};
      s.duration = std::min(s.duration, 64 / k);
      s.record_interval = s.duration / 4;
    }
    // Scaled by 2^e, |e| ≤ 20, and translated by up to 2^30 (fixed: |e| ≤ 8,
    // 2^20: squared distances and their products stay far inside ±2^63).
    bool moved = false;
    if (o.wide && *rc::gen::weightedElement<bool>({{3, false}, {1, true}})) {
      int e = centred(o.fixed_mode ? 8 : 20);
      // Fixed mode: fast scenes (speeds up to 2^12) scaled up by 2^8 reach
      // (Δp × Δv)² ~ 2^63, which fixed point rightly refuses as overflow:
      // they are only scaled down.
      if (o.fixed_mode && family == fast && e > 0) e = -e;
      Point offset{0, 0};
      if (*rc::gen::arbitrary<bool>()) {
        const double fraction = centred(1024) / 1024.0;  // one draw per statement (random_box_scene)
        offset = {std::ldexp(fraction, *rc::gen::inRange(0, o.fixed_mode ? 21 : 31)),
                  std::ldexp(1.0, centred(o.fixed_mode ? 20 : 30))};
      }
      transform(s, e, offset);
      RC_PRE(valid(s));
      moved = true;
    }
    // Dissipative: the default (which no generated ball or wall uses) below 1 too.
    if (o.dissipative) s.restitution = 63 / 64.0;
    return GeneratedScene{s, family, moved};
  });
}

// Piles (scene_generators.hpp). Kinds: radius k/64, k 4–16 (1/16 to 1/4),
// mass 1 + k/4 (1 to 4), restitution k/128, k 39–121 (0.305 to 0.945); the
// walls share one restitution from the same range, and so does the scene's
// default. The grid: cells 4 r_max, as many columns as √(the largest count)
// (at least 3; from the largest count, not from n, so that shrinking n leaves
// the other balls where they were), centres within r_max/2 of their cell's
// centre (≥ 3 r_max apart, ≥ 1.5 r_max from the cell's border), velocities
// k/64 with |k| ≤ 16 per component. The floor, from x = 0 to W (the grid's
// width): one slanted wall falling to the right or to the left, slope k/8,
// k 1–4, or two meeting at x = W/2 (a V); the grid starts at the floor's
// highest point (a ball of the lowest row is ≥ 1.5 r_max cos 27° > r_max
// from it). Vertical side walls and a lid g/2 + 4 r_max above the grid (room
// for the dropped ball of wake-keeps-momentum). Gravity (0, −g), g k/4,
// k 8–80 (2 to 20).
rc::Gen<GeneratedPile> pile_scene() {
  return rc::gen::exec([] {
    const int size = *rc::gen::withSize([](int n) { return rc::gen::just(n); });
    const int max_n = std::clamp(10 + size / 8, 10, 200);
    const int n = *rc::gen::inRange(10, max_n + 1);
    GeneratedPile pile;
    pile.kinds = *rc::gen::inRange(1, 4);
    std::vector<BallSpec> kinds;
    int r_max64 = 0;
    for (int k = 0; k < pile.kinds; ++k) {
      BallSpec b;
      const int r64 = *rc::gen::inRange(4, 17);
      r_max64 = std::max(r_max64, r64);
      b.radius = r64 / 64.0;
      b.mass = 1 + *rc::gen::inRange(0, 13) / 4.0;
      b.restitution = *rc::gen::inRange(39, 122) / 128.0;
      kinds.push_back(b);
    }
    const double r_max = r_max64 / 64.0, cell = 4 * r_max;
    const double g = *rc::gen::inRange(8, 81) / 4.0;
    const double wall_e = *rc::gen::inRange(39, 122) / 128.0;
    pile.shape = *rc::gen::inRange(0, 3);
    const double slope = *rc::gen::inRange(1, 5) / 8.0;
    const int cols = std::max(3, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(max_n)))));
    const int rows = (max_n + cols - 1) / cols;
    const double W = cols * cell;
    Scene& s = pile.scene;
    s.name = "pile";
    s.gravity = {0, -g};
    s.restitution = wall_e;
    double left = 0, right = 0, floor_top = 0;  // the floor's height at x = 0 and x = W, its highest point
    if (pile.shape == 0) left = floor_top = slope * W;
    if (pile.shape == 1) right = floor_top = slope * W;
    if (pile.shape == 2) {
      left = right = floor_top = slope * W / 2;
      s.walls.push_back({{0, left}, {W / 2, 0}, wall_e});
      s.walls.push_back({{W / 2, 0}, {W, right}, wall_e});
    } else {
      s.walls.push_back({{0, left}, {W, right}, wall_e});
    }
    const double lid = floor_top + rows * cell + g / 2 + 4 * r_max;
    s.walls.push_back({{W, right}, {W, lid}, wall_e});
    s.walls.push_back({{W, lid}, {0, lid}, wall_e});
    s.walls.push_back({{0, lid}, {0, left}, wall_e});
    for (int k = 0; k < n; ++k) {
      BallSpec b = kinds[*rc::gen::inRange<std::size_t>(0, kinds.size())];
      b.position = {(k % cols + 0.5) * cell + centred(r_max64) / 128.0,
                    floor_top + (k / cols + 0.5) * cell + centred(r_max64) / 128.0};
      b.velocity = {sixty_fourths(16), sixty_fourths(16)};
      s.balls.push_back(b);
    }
    const std::optional<PileBounds> bounds = pile_bounds(s);
    RC_PRE(bounds.has_value());
    s.duration = bounds->until();
    s.record_interval = 1.0 / 8;
    RC_PRE(valid(s));
    return pile;
  });
}

void showValue(const GeneratedPile& generated, std::ostream& os) { showValue(generated.scene, os); }

void tag_pile_features(const GeneratedPile& g) {
  const std::size_t n = g.scene.balls.size();
  double e = 0;
  for (const BallSpec& b : g.scene.balls) e = std::max(e, b.restitution);
  for (const WallSpec& w : g.scene.walls) e = std::max(e, w.restitution);
  static const char* shapes[] = {"floor down to the right", "floor down to the left", "V floor"};
  static const char* kinds[] = {"1 kind", "2 kinds", "3 kinds"};
  RC_TAG("pile", shapes[g.shape], kinds[g.kinds - 1], n <= 15 ? "10-15 balls" : n <= 30 ? "16-30 balls" : n <= 100 ? "31-100 balls" : "101-200 balls",
         e < 0.6 ? "e < 0.6" : e < 0.85 ? "e 0.6-0.85" : "e >= 0.85");
}

rc::Gen<Scene> bounce_scene() {
  return rc::gen::exec([] {
    Scene s;
    s.name = "bounce";
    const double g = *rc::gen::inRange(4, 81) / 4.0;
    s.gravity = {0, -g};
    s.walls.push_back({{-1, 0}, {1, 0}, 1.0});
    BallSpec b;
    b.radius = *rc::gen::inRange(4, 17) / 64.0;
    b.restitution = *rc::gen::inRange(39, 122) / 128.0;
    const double h = *rc::gen::inRange(1, 33) / 16.0;
    b.position = {0, b.radius + h};
    b.velocity = {0, 0};
    s.balls.push_back(b);
    const double e = b.restitution;
    s.duration = std::ceil(std::sqrt(2 * h / g) + 2 * e * std::sqrt(2 * g * h) / (g * (1 - e))) + 1;
    s.record_interval = 1.0 / 8;
    RC_PRE(valid(s));
    return s;
  });
}

rc::Gen<Scene> struck_sleeper_scene() {
  return rc::gen::exec([] {
    Scene s;
    s.name = "struck_sleeper";
    const double g = *rc::gen::inRange(4, 81) / 4.0;
    s.gravity = {0, -g};
    s.walls.push_back({{-2, 0}, {2, 0}, *rc::gen::inRange(39, 122) / 128.0});
    BallSpec lying, dropped;
    for (BallSpec* b : {&lying, &dropped}) {
      b->radius = *rc::gen::inRange(4, 17) / 64.0;
      b->mass = 1 + *rc::gen::inRange(0, 13) / 4.0;
      b->restitution = *rc::gen::inRange(39, 122) / 128.0;
      b->velocity = {0, 0};
    }
    const double reach = lying.radius + dropped.radius;
    const int k_magnitude = *rc::gen::inRange(1, 57);  // one draw per statement (random_box_scene)
    const int k = k_magnitude * (*rc::gen::arbitrary<bool>() ? 1 : -1);
    const double h = *rc::gen::inRange(8, 33) / 16.0;
    lying.position = {0, lying.radius};
    dropped.position = {k / 64.0 * reach, 2 * lying.radius + dropped.radius + h};
    s.balls = {lying, dropped};
    s.duration = std::ceil(std::sqrt(2 * (h + reach) / g)) + 1;
    s.record_interval = 1.0 / 8;
    RC_PRE(valid(s));
    return s;
  });
}

// A dense gas in a box, for the gas engine (gas_engine.hpp) against
// EventEngine: 30 to 150 balls of two sizes and masses on a jittered lattice
// at a packing fraction of 0.1 to 0.5, random velocities, one restitution
// (1 in half the cases), a slanted wall with two round ends inside, 2 to 4
// s: enough events a case for stale contacts, crossings and walls to come
// in every order. In a third of the cases a row of three balls, the last
// two touching, is struck at t = 1: a jam, where the gas engine hands the
// run over.
rc::Gen<Scene> dense_gas_scene() {
  return rc::gen::exec([] {
    Scene s;
    s.name = "dense_gas";
    s.gravity = {0, 0};
    const int n = *rc::gen::inRange(30, 151);
    const double eta = *rc::gen::inRange(2, 11) / 20.0;
    const double e = *rc::gen::arbitrary<bool>() ? 1.0 : *rc::gen::inRange(64, 128) / 128.0;
    s.restitution = e;
    const double r_small = 0.25, r_large = 0.375;
    const int side = 1 + static_cast<int>(std::sqrt(static_cast<double>(n)));
    // The lattice's spacing from the packing fraction (the mean area a ball).
    const double mean_area = 3.14159 * (r_small * r_small + r_large * r_large) / 2;
    const double spacing = std::max(std::sqrt(mean_area / eta), 2 * r_large + 0.05);
    const double L = side * spacing;
    s.walls = {{{0, 0}, {L, 0}, e}, {{L, 0}, {L, L}, e}, {{L, L}, {0, L}, e}, {{0, L}, {0, 0}, e}};
    s.walls.push_back({{0.3 * L, 0.7 * L}, {0.6 * L, 0.55 * L}, e});
    const bool jam = *rc::gen::inRange(0, 3) == 0;
    for (int k = 0; k < n; ++k) {
      BallSpec b;
      const bool large = *rc::gen::inRange(0, 3) == 0;
      b.radius = large ? r_large : r_small;
      b.mass = large ? 2.25 : 1.0;
      b.restitution = e;
      const double slack = (spacing - 2 * b.radius) / 2 - 0.01;
      b.position = {(k % side + 0.5) * spacing + slack * *rc::gen::inRange(-64, 65) / 64.0,
                    (k / side + 0.5) * spacing + slack * *rc::gen::inRange(-64, 65) / 64.0};
      b.velocity = {*rc::gen::inRange(-64, 65) / 32.0, *rc::gen::inRange(-64, 65) / 32.0};
      if (jam && k / side == 0) continue;  // the bottom row is the jam's
      const double clearance =
          distance_to_segment<double>({b.position[0], b.position[1]}, {{0.3 * L, 0.7 * L}, {0.6 * L, 0.55 * L}});
      if (clearance < b.radius + 0.01) continue;  // on the inner wall
      s.balls.push_back(b);
    }
    if (jam) {
      // Speed 1 across a gap of 1 (centres 1 + 2r apart): struck at t = 1,
      // and the struck ball touches the third already (centres 2r apart).
      const double y = 0.5 * spacing, r = r_small, x0 = 2 * r + 0.01;
      s.balls.push_back({});
      s.balls.back().position = {x0, y};
      s.balls.back().velocity = {1, 0};
      for (double x : {x0 + 1 + 2 * r, x0 + 1 + 4 * r}) {
        BallSpec b;
        b.position = {x, y};
        b.velocity = {0, 0};
        s.balls.push_back(b);
      }
      for (std::size_t k = s.balls.size() - 3; k < s.balls.size(); ++k)
        s.balls[k].radius = r, s.balls[k].mass = 1, s.balls[k].restitution = e;
    }
    s.duration = *rc::gen::inRange(2, 5);
    s.record_interval = 0.25;
    RC_TAG(jam ? "a jam" : "no jam");
    RC_TAG(e == 1 ? "elastic" : "inelastic");
    RC_TAG(eta < 0.25 ? "eta < 0.25" : "eta >= 0.25");
    RC_PRE(valid(s));
    return s;
  });
}

}  // namespace collide2d::properties
