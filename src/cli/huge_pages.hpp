// Memory in transparent huge pages for the whole process.
//
// A large event-driven run is bound by address translation: every event
// touches a few dozen cache lines of balls anywhere in the box (bodies,
// event lists, cells, the calendar), and with 4 KiB pages nearly each is a
// TLB miss as well. glibc's malloc asks for transparent huge pages
// (madvise) when its tunable glibc.malloc.hugetlb=1 is set, which made the
// 10^6-disc gas 1.6× as fast, and the 10^4-disc one 1.3× (README,
// "Huge pages"). Tunables are read once, when a process starts, so
// collide2d sets it and executes itself again before anything else
// happens. Nothing computed changes: the same bits, only faster.
//
// Not done when GLIBC_TUNABLES names the tunable already (the user's
// choice, or the second start), when COLLIDE2D_NO_HUGE_PAGES is set, or off
// glibc; if the new start fails, the program goes on as it is.
#pragma once

namespace collide2d::cli {

void restart_with_huge_pages(char** argv);

// What this process's malloc does, for --version: "memory: transparent huge
// pages (glibc.malloc.hugetlb=1)" or "memory: ordinary pages".
const char* memory_pages_line();

}  // namespace collide2d::cli
