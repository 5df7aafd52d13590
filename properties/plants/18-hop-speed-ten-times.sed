# target: src/collide2d/sim/contact_rules.hpp
# The hop speed is ten times sqrt(2 g_n h_rest): hops a hundred times too high collapse.
s|Num hop_speed(const Num& g_n) const { return NumberTraits<Num>::sqrt(num<Num>(2.0) \* g_n) \* sqrt_height_; }|Num hop_speed(const Num\& g_n) const { return num<Num>(10.0) * NumberTraits<Num>::sqrt(num<Num>(2.0) * g_n) * sqrt_height_; }|
