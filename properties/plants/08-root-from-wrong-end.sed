# target: src/collide2d/toi/quadratic.hpp
# The root from the wrong end: the upward crossing (separation) instead of the downward one (contact).
s|numerator = b < zero ? C : b + sqrt_d;|numerator = b < zero ? C : b - sqrt_d;|
s|denominator = b < zero ? sqrt_d - b : -A;|denominator = b < zero ? -sqrt_d - b : -A;|
