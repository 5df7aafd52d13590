#include "cli/huge_pages.hpp"

#include <cstdlib>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

namespace collide2d::cli {

void restart_with_huge_pages(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  if (std::getenv("COLLIDE2D_NO_HUGE_PAGES") != nullptr) return;
  // glibc.malloc.hugetlb came with glibc 2.35; older ones would ignore it.
  if (__GLIBC__ < 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ < 35)) return;
  const char* set = std::getenv("GLIBC_TUNABLES");
  std::string tunables = set ? set : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  const std::string before = tunables;
  tunables += tunables.empty() ? "glibc.malloc.hugetlb=1" : ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the restart failed (no /proc, qemu-user without binfmt_misc);
  // go on with ordinary pages, and say so (memory_pages_line).
  if (set) setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

const char* memory_pages_line() {
  const char* set = std::getenv("GLIBC_TUNABLES");
  const std::string tunables = set ? set : "";
  return tunables.find("glibc.malloc.hugetlb=1") != std::string::npos ? "memory: transparent huge pages (glibc.malloc.hugetlb=1)"
                                                                       : "memory: ordinary pages";
}

}  // namespace collide2d::cli
