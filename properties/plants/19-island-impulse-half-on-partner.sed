# target: src/collide2d/sim/contact_graph.hpp
# A resting-contact rule's impulse (an island's impact: a held strike, a plastic impact, a hold, a renewal) gives the contact's second ball half its share: momentum is not kept.
s|push(world.balls\[c.j\], -(s.x\[r\] \* c.normal), \[\](Body<Num>& b, const Vec2<Num>& dv) { b.velocity = b.velocity + dv; });|push(world.balls[c.j], -(num<Num>(0.5) * s.x[r] * c.normal), [](Body<Num>\& b, const Vec2<Num>\& dv) { b.velocity = b.velocity + dv; });|
