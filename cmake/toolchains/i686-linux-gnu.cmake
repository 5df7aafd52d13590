# Cross build for 32-bit x86 (Debian i386), run under qemu-i386. No __int128
# here (fixed mode takes numeric/portable_int128.hpp), and double arithmetic
# defaults to the x87 unit: the strict_fp flags force SSE2.
set(CMAKE_SYSTEM_PROCESSOR i686)
set(COLLIDE2D_CROSS_TRIPLET i686-linux-gnu)
set(COLLIDE2D_CROSS_MULTIARCH i386-linux-gnu)
set(COLLIDE2D_CROSS_DEB_ARCH i386)
set(COLLIDE2D_CROSS_QEMU qemu-i386)
include(${CMAKE_CURRENT_LIST_DIR}/cross-common.cmake)
