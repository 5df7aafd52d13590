# target: src/collide2d/sim/contact_rules.hpp
# The article's two-ball formula (momentum kept only for equal masses) in place of two_ball_impulse_response.
s|two_ball_impulse_response(a.velocity, b->velocity, a.mass, b->mass, c.normal, restitution)|article_two_ball_response(a.velocity, b->velocity, a.mass, b->mass, c.normal, restitution, restitution)|
