# target: src/toi/quadratic.hpp
# A sign flip in the contact root of a quadratic: C / (sqrt(D) + b) for C / (sqrt(D) - b).
s|const Num t = b < zero ? C / (sqrt_d - b) : -(b + sqrt_d) / A;|const Num t = b < zero ? C / (sqrt_d + b) : -(b + sqrt_d) / A;|
