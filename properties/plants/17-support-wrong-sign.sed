# target: src/collide2d/sim/contact_rules.hpp
# The island support test with the wrong sign: an island sleeps when its contact forces leave a ball accelerating, not when they hold every ball still.
s/if (!(length_squared(b.velocity) < th_.speed \* th_.speed) || least < length_squared(b.acceleration)) return false;/if (!(length_squared(b.velocity) < th_.speed * th_.speed) || !(least < length_squared(b.acceleration))) return false;/
