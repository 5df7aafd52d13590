# target: src/collide2d/sim/event_engine.hpp
# An island's forces solved again give a new version to its first ball only: the others' events predicted from their old motion stay current and are acted on after they changed course.
s|      motion_changed(x, MotionChange::forces);|      if (x == balls.front()) motion_changed(x, MotionChange::forces);|
