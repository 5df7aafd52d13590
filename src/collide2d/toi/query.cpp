#include "collide2d/toi/query.hpp"

namespace collide2d {

QueryAnswer answer_toi_query(const ToiQuery& q, ToiMethod method, NumberMode mode, double eps) {
  return with_number_type(mode, [&](auto type) {
    using Num = typename decltype(type)::type;
    const auto r = solve_toi_query<Num>(convert_query<Num>(q), method, num<Num>(eps));
    return QueryAnswer{r.hit(), NumberTraits<Num>::to_double(r.time)};
  });
}

}  // namespace collide2d
