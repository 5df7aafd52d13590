# target: src/collide2d/sim/event_queue.hpp
# An off-by-one in the tie-break of simultaneous events (LaterEvent): adjacent first indices compare equal.
s|if (x.a != y.a) return y.a < x.a;|if (x.a != y.a) return y.a + 1 < x.a;|
