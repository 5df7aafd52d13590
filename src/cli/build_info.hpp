// What built this program: its version and compiler, for `--version` and the
// provenance of run files and studies; and when a file was made.
#pragma once

#include <ctime>
#include <string>

#include "collide2d/numeric/fixed.hpp"
#include "collide2d/version.hpp"

namespace collide2d::cli {

// Now, in UTC, as 2026-11-27T09:53:48Z (the `created` of studies and sweeps).
inline std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return buf;
}

inline std::string compiler_description() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "gcc " __VERSION__;
#else
  return "unknown";
#endif
}

// `collide2d --version`: the version, then how the arithmetic was built (the
// determinism promise depends on it).
inline std::string version_text() {
  return std::string("collide2d ") + COLLIDE2D_VERSION + "\n" + "compiler " + compiler_description() +
         "\narchitecture " +
#if defined(__x86_64__)
         "x86-64" +
#elif defined(__i386__)
         "i686" +
#elif defined(__aarch64__)
         "aarch64" +
#elif defined(__powerpc64__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
         "ppc64le" +
#else
         "other" +
#endif
         "\nstrict mode: IEEE binary64, no FMA contraction, no fast-math" +
#if defined(__SSE2_MATH__)
         ", SSE2" +
#endif
         "\nfixed mode: Q63.64 in " + (fixed_detail::kNativeInt128 ? "__int128" : "two 64-bit words") +
         ", overflow reported";
}

}  // namespace collide2d::cli
