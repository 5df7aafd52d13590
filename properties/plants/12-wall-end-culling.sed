# target: src/collide2d/toi/analytic.hpp
# The bounding-box test of a wall's round ends forgets the radius: ends a ball passes within r of are skipped.
s|const Num reach = r + r \* num<Num>(0x1p-40);|const Num reach = r * num<Num>(0x1p-40);|
