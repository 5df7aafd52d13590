# target: src/collide2d/geometry/vec2.hpp
# The motion model drops the 1/2: p + v t + a t^2.
s|return {p.x + t \* (v.x + half_t \* a.x), p.y + t \* (v.y + half_t \* a.y)};|return {p.x + t * (v.x + t * a.x), p.y + t * (v.y + t * a.y)};|
