// A collide2d scene in Box2D 2.4 (see peer_run.hpp for the settings).
#include <box2d/box2d.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "peers/peer_run.hpp"

namespace collide2d {

PeerRun run_box2d(const Scene& scene, double until, double sample_every, bool zero_restitution_threshold) {
  PeerRun out;
  out.engine = zero_restitution_threshold ? "box2d_threshold0" : "box2d";
  auto world = std::make_unique<b2World>(b2Vec2(static_cast<float>(scene.gravity[0]), static_cast<float>(scene.gravity[1])));
  b2BodyDef ground_def;
  b2Body* ground = world->CreateBody(&ground_def);
  for (const WallSpec& w : scene.walls) {
    b2EdgeShape edge;
    edge.SetTwoSided(b2Vec2(static_cast<float>(w.a[0]), static_cast<float>(w.a[1])),
                     b2Vec2(static_cast<float>(w.b[0]), static_cast<float>(w.b[1])));
    b2FixtureDef f;
    f.shape = &edge;
    f.friction = 0;
    f.restitution = static_cast<float>(w.restitution);
    if (zero_restitution_threshold) f.restitutionThreshold = 0;
    ground->CreateFixture(&f);
  }
  std::vector<b2Body*> bodies;
  for (const BallSpec& b : scene.balls) {
    b2BodyDef def;
    def.type = b.fixed ? b2_staticBody : b2_dynamicBody;
    def.position.Set(static_cast<float>(b.position[0]), static_cast<float>(b.position[1]));
    def.linearVelocity.Set(static_cast<float>(b.velocity[0]), static_cast<float>(b.velocity[1]));
    def.fixedRotation = true;
    b2Body* body = world->CreateBody(&def);
    b2CircleShape circle;
    circle.m_radius = static_cast<float>(b.radius);
    b2FixtureDef f;
    f.shape = &circle;
    f.density = static_cast<float>(b.mass / (std::numbers::pi * b.radius * b.radius));  // the scene's mass
    f.friction = 0;
    f.restitution = static_cast<float>(b.restitution);
    if (zero_restitution_threshold) f.restitutionThreshold = 0;
    body->CreateFixture(&f);
    bodies.push_back(body);
  }
  auto sample = [&] {
    PeerSample s;
    for (b2Body* body : bodies) {
      s.position.push_back({body->GetPosition().x, body->GetPosition().y});
      s.velocity.push_back({body->GetLinearVelocity().x, body->GetLinearVelocity().y});
    }
    return s;
  };
  step_and_sample(out, scene, until, sample_every, [&](double dt) { world->Step(static_cast<float>(dt), 8, 3); }, sample);
  return out;
}

}  // namespace collide2d
