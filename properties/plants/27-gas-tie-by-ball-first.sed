# target: src/collide2d/sim/gas_engine.hpp
# The gas engine's queue orders events of one instant by the ball holding them before their kind and indices: simultaneous events are processed in another order than EventEngine's.
s|      return x.order < y.order;|      if (x.ball() != y.ball()) return x.ball() < y.ball();\n      return x.order < y.order;|
