# target: src/collide2d/toi/analytic.hpp
# The wall normal left unnormalised in prepare_wall: perp(d) for perp(d) / |d|.
s|g.unit_normal = normalized(perp(g.direction.hi));|g.unit_normal = perp(g.direction.hi);|
