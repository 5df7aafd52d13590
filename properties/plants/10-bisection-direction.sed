# target: src/collide2d/toi/article_methods.hpp
# Step-and-bisect keeps the wrong half of the step.
s|if (g < zero) hi = mid; else lo = mid;|if (g < zero) lo = mid; else hi = mid;|
