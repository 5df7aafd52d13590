# target: src/toi/quadratic.hpp
# The root from the wrong end: the upward crossing (separation) instead of the downward one (contact).
s|const Num t = b < zero ? C / (sqrt_d - b) : -(b + sqrt_d) / A;|const Num t = b < zero ? C / (-sqrt_d - b) : -(b - sqrt_d) / A;|
