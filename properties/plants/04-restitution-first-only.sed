# target: src/collide2d/response/response.hpp
# A contact restitution of e1 alone for e1 * e2 (the second object ignored).
s|inline Num contact_restitution(const Num\& e1, const Num\& e2) { return e1 \* e2; }|inline Num contact_restitution(const Num\& e1, const Num\&) { return e1; }|
