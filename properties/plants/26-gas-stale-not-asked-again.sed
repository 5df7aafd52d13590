# target: src/collide2d/sim/gas_engine.hpp
# The gas engine drops a stale contact without asking its owner for its next one: contacts a list of every prediction would have held are lost.
s|        predict_contacts_after(owner, e, true);|        place(owner);|
