# target: src/collide2d/toi/analytic.hpp
# The time of impact with a wall's round end returns the normal from the ball's centre to the end, not from the end to the centre.
s|      best.normal = normalized(position_at(ball, root.t) - end);|      best.normal = normalized(end - position_at(ball, root.t));|
