# target: src/collide2d/toi/analytic.hpp
# The time of impact of two balls returns the normal from the first ball's centre to the other's (towards the other ball, not towards the first).
s|  r.normal = normalized(pa - pb);|  r.normal = normalized(pb - pa);|
