# target: src/collide2d/toi/analytic.hpp
# The time of impact with a wall's face returns the face's normal on the wrong side (away from the ball), and its contact point with it.
s|    hit.normal = side < 0 ? -wall.unit_normal : wall.unit_normal;|    hit.normal = side < 0 ? wall.unit_normal : -wall.unit_normal;|
