# Cross build for 64-bit little-endian POWER (Debian ppc64el), run under
# qemu-ppc64le. gcc contracts into fmadd by default here as well; the strict
# flags and the start-up FPSCR check apply.
set(CMAKE_SYSTEM_PROCESSOR ppc64le)
set(COLLIDE2D_CROSS_TRIPLET powerpc64le-linux-gnu)
set(COLLIDE2D_CROSS_MULTIARCH powerpc64le-linux-gnu)
set(COLLIDE2D_CROSS_DEB_ARCH ppc64el)
set(COLLIDE2D_CROSS_QEMU qemu-ppc64le)
include(${CMAKE_CURRENT_LIST_DIR}/cross-common.cmake)
