# target: src/collide2d/response/response.hpp
# A sign flip in the reflection about a wall: v + (1 + e)(v.n) n for v - (1 + e)(v.n) n.
s|return {v.x - k \* n.x, v.y - k \* n.y};|return {v.x + k * n.x, v.y + k * n.y};|
