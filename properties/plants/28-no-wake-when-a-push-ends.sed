# target: src/collide2d/sim/event_engine_rest.hpp
# A sleeper is never asked again when a contact with a moving ball ends: a ball pushed to sleep stays where nothing carries it.
s|  std::vector<int>& asked = graph_.parted();|  std::vector<int>\& asked = graph_.parted();\n  asked.clear();|
