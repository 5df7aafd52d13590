# target: src/collide2d/sim/simulate.cpp
# The default rest height is ten times the documented 1e-6 of the smallest radius.
s|s.height = scene.rest.height.value_or(1e-6 \* r_min);|s.height = scene.rest.height.value_or(1e-5 * r_min);|
