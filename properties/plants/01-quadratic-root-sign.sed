# target: src/collide2d/toi/quadratic.hpp
# A sign flip in the contact root of a quadratic: C / (sqrt(D) + b) for C / (sqrt(D) - b).
s|denominator = b < zero ? sqrt_d - b : -A;|denominator = b < zero ? sqrt_d + b : -A;|
