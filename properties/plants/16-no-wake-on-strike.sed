# target: src/collide2d/sim/contact_rules.hpp
# A strike never wakes a sleeping ball: the striker bounces off it as off a fixed ball.
s|bool wakes(const Num& closing) const { return !(closing < th_.speed); }|bool wakes(const Num\& closing) const { return closing < closing; }|
