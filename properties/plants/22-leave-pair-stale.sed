# target: src/collide2d/sim/event_engine.hpp
# A pair's leave event is not checked against its second ball's version: a contact ends on a prediction made before that ball changed course.
s|    return !between_two_balls(e.kind) \|\| world_.balls\[e.b\].version == e.version_b;|    return e.kind != EventKind::ball_ball \|\| world_.balls[e.b].version == e.version_b;|
