# target: src/collide2d/sim/contact_graph.hpp
# A strike answered along the held contacts' free part (a wedge) kicks every ball of it by the impulse over the first ball's mass, not its own.
s|s.kick.push_back({ball, (impulse / world.balls\[ball\].mass) \* dx});|s.kick.push_back({ball, (impulse / world.balls[d.front().first].mass) * dx});|
