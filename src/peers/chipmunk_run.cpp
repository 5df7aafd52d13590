// A collide2d scene in Chipmunk 7 (see peer_run.hpp for the settings).
#include <chipmunk/chipmunk.h>

#include <unistd.h>

#include <cstdio>
#include <cmath>

#include "peers/peer_run.hpp"

namespace collide2d {

PeerRun run_chipmunk(const Scene& scene, double until, double sample_every) {
  PeerRun out;
  out.engine = "chipmunk";
  cpSpace* space = cpSpaceNew();
  cpSpaceSetGravity(space, cpv(scene.gravity[0], scene.gravity[1]));
  cpBody* ground = cpSpaceGetStaticBody(space);
  std::vector<cpShape*> walls;
  for (const WallSpec& w : scene.walls) {
    cpShape* seg = cpSpaceAddShape(space, cpSegmentShapeNew(ground, cpv(w.a[0], w.a[1]), cpv(w.b[0], w.b[1]), 0));
    cpShapeSetElasticity(seg, w.restitution);
    cpShapeSetFriction(seg, 0);
    walls.push_back(seg);
  }
  std::vector<cpBody*> bodies;
  std::vector<cpShape*> shapes;
  for (const BallSpec& b : scene.balls) {
    cpBody* body = b.fixed ? cpSpaceAddBody(space, cpBodyNewStatic())
                           : cpSpaceAddBody(space, cpBodyNew(b.mass, INFINITY));  // infinite moment: no rotation
    cpBodySetPosition(body, cpv(b.position[0], b.position[1]));
    if (!b.fixed) cpBodySetVelocity(body, cpv(b.velocity[0], b.velocity[1]));
    cpShape* circle = cpSpaceAddShape(space, cpCircleShapeNew(body, b.radius, cpvzero));
    cpShapeSetElasticity(circle, b.restitution);
    cpShapeSetFriction(circle, 0);
    bodies.push_back(body);
    shapes.push_back(circle);
  }
  auto sample = [&] {
    PeerSample s;
    for (cpBody* body : bodies) {
      const cpVect p = cpBodyGetPosition(body), v = cpBodyGetVelocity(body);
      s.position.push_back({p.x, p.y});
      s.velocity.push_back({v.x, v.y});
    }
    return s;
  };
  step_and_sample(out, scene, until, sample_every, [&](double dt) { cpSpaceStep(space, dt); }, sample);
  for (std::vector<cpShape*>* list : {&walls, &shapes})
    for (cpShape* shape : *list) {
      cpSpaceRemoveShape(space, shape);
      cpShapeFree(shape);
    }
  for (cpBody* body : bodies) {
    cpSpaceRemoveBody(space, body);
    cpBodyFree(body);
  }
  cpSpaceFree(space);
  return out;
}

// Debian's Chipmunk is a debug build: its first space prints a banner on
// standard output, which would break the CSV. It is sent to standard error.
void start_chipmunk() {
  std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO);
  dup2(STDERR_FILENO, STDOUT_FILENO);
  cpSpaceFree(cpSpaceNew());
  std::fflush(stdout);
  dup2(saved, STDOUT_FILENO);
  close(saved);
}

}  // namespace collide2d
