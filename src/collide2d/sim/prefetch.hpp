// Asking the memory early for what an event will read (a hint: no result,
// no order, no bit depends on it).
//
// Always inlined, for a reason that is easy to miss: GCC counts a prefetch
// as having no side effect, so a function that only prefetches is "pure",
// and a call to it that is not inlined is deleted as dead code. The queue's
// look-ahead (EventQueue::prefetch_next) was compiled to nothing that way
// at -O1 and above until these were forced inline.
#pragma once

#include <cstddef>

namespace collide2d {

// Every cache line of *x (a ball's body or event list spans two or three).
template <class T>
[[gnu::always_inline]] inline void prefetch_object(const T* x) {
  const char* at = reinterpret_cast<const char*>(x);
  for (std::size_t k = 0; k < sizeof(T); k += 64) __builtin_prefetch(at + k);
  __builtin_prefetch(at + sizeof(T) - 1);
}

// Element i of v, if it has one.
template <class Vector>
[[gnu::always_inline]] inline void prefetch_element(const Vector& v, int i) {
  if (i >= 0 && static_cast<std::size_t>(i) < v.size()) prefetch_object(&v[static_cast<std::size_t>(i)]);
}

}  // namespace collide2d
