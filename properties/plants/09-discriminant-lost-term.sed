# target: src/collide2d/numeric/number_traits.hpp
# A lost compensation term in the exact difference of products behind compensated_discriminant: cd.lo dropped.
s|return (ab.hi - cd.hi) + (ab.lo - cd.lo);|return (ab.hi - cd.hi) + ab.lo;|
