#!/bin/bash
# collide2d restarts itself with malloc's memory in transparent huge pages
# (src/cli/huge_pages.hpp): --version says so, COLLIDE2D_NO_HUGE_PAGES turns
# it off, and a run gives the same bits either way (only its speed changes).
set -euo pipefail
exe=$1
scene=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
env -u GLIBC_TUNABLES "$exe" --version | grep -qx 'memory: transparent huge pages (glibc.malloc.hugetlb=1)' ||
  { echo "FAIL: --version does not report huge pages"; env -u GLIBC_TUNABLES "$exe" --version; exit 1; }
env -u GLIBC_TUNABLES COLLIDE2D_NO_HUGE_PAGES=1 "$exe" --version | grep -qx 'memory: ordinary pages' ||
  { echo "FAIL: COLLIDE2D_NO_HUGE_PAGES=1 still asks for huge pages"; exit 1; }
# A user's own tunables are kept, with the one for huge pages added.
GLIBC_TUNABLES=glibc.malloc.check=0 "$exe" --version | grep -qx 'memory: transparent huge pages (glibc.malloc.hugetlb=1)' ||
  { echo "FAIL: other tunables set: huge pages not added"; exit 1; }
hash_huge=$(env -u GLIBC_TUNABLES "$exe" run "$scene" -o "$dir/huge.h5" | grep 'final hash')
hash_plain=$(env -u GLIBC_TUNABLES COLLIDE2D_NO_HUGE_PAGES=1 "$exe" run "$scene" -o "$dir/plain.h5" | grep 'final hash')
echo "huge pages:     $hash_huge"
echo "ordinary pages: $hash_plain"
[ -n "$hash_huge" ] && [ "$hash_huge" = "$hash_plain" ] || { echo "FAIL: the pages changed the bits"; exit 1; }
