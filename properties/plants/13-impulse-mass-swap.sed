# target: src/collide2d/response/response.hpp
# The second ball's velocity change divided by the first ball's mass.
s|const Num dv1 = J / m1, dv2 = J / m2;|const Num dv1 = J / m1, dv2 = J / m1;|
