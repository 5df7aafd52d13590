# Cross build for 64-bit ARM (Debian arm64), run under qemu-aarch64.
# gcc contracts a*b+c into fmadd by default here: the strict_fp flags
# (-ffp-contract=off) and the start-up FPCR check keep strict mode IEEE.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(COLLIDE2D_CROSS_TRIPLET aarch64-linux-gnu)
set(COLLIDE2D_CROSS_MULTIARCH aarch64-linux-gnu)
set(COLLIDE2D_CROSS_DEB_ARCH arm64)
set(COLLIDE2D_CROSS_QEMU qemu-aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/cross-common.cmake)
