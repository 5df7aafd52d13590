# Shared by the three cross toolchain files (issue 15). The including file sets
# COLLIDE2D_CROSS_TRIPLET (gcc's prefix), COLLIDE2D_CROSS_DEB_ARCH (Debian's
# name, the sysroot's folder), COLLIDE2D_CROSS_QEMU and CMAKE_SYSTEM_PROCESSOR.
#
# The sysroot is the target's Debian packages unpacked by .ci/install-cross-deps
# (glibc, libstdc++, HDF5 and its closure, RapidCheck, Boost, and the
# header-only nlohmann-json, CLI11, Eigen, Catch2). Everything the build finds
# comes from there and nothing from the host's /usr, whose headers and
# libraries are x86-64's. qemu runs the test binaries with the same directory
# as its -L root, so the dynamic loader and every shared library are the
# target's.
set(CMAKE_SYSTEM_NAME Linux)

set(COLLIDE2D_CROSS_ROOT "$ENV{COLLIDE2D_CROSS_ROOT}")
if(NOT COLLIDE2D_CROSS_ROOT)
  set(COLLIDE2D_CROSS_ROOT /opt/collide2d-cross)
endif()
set(_sysroot "${COLLIDE2D_CROSS_ROOT}/${COLLIDE2D_CROSS_DEB_ARCH}")
if(NOT EXISTS "${_sysroot}/.collide2d-sysroot")
  message(FATAL_ERROR "No ${COLLIDE2D_CROSS_DEB_ARCH} sysroot at ${_sysroot}: run .ci/install-cross-deps ${COLLIDE2D_CROSS_DEB_ARCH} (as root)")
endif()

set(CMAKE_C_COMPILER ${COLLIDE2D_CROSS_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${COLLIDE2D_CROSS_TRIPLET}-g++)
set(CMAKE_SYSROOT "${_sysroot}")
set(CMAKE_LIBRARY_ARCHITECTURE ${COLLIDE2D_CROSS_MULTIARCH})

# Programs (the host's cmake, bash, python) from the host; libraries, headers
# and package configurations only from the sysroot.
set(CMAKE_FIND_ROOT_PATH "${_sysroot}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# FindHDF5 would otherwise run the host's h5cc and read the host's paths from
# it; a wrapper that fails sends it to its plain header and library search,
# which finds include/hdf5/serial and lib/<multiarch>/hdf5/serial in the sysroot.
set(HDF5_C_COMPILER_EXECUTABLE /bin/false CACHE FILEPATH "no HDF5 wrapper when cross-compiling")

# The shared libraries' own dependencies (libcurl, libssl, ... under libhdf5)
# are resolved inside the sysroot at link time.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,-rpath-link,${_sysroot}/usr/lib/${COLLIDE2D_CROSS_MULTIARCH}")

# ctest and add_test(... $<TARGET_FILE:...>) run target binaries through qemu.
# COLLIDE2D_NO_HUGE_PAGES: collide2d would execute itself again for huge pages
# (src/cli/huge_pages.hpp), and under qemu-user that second start would not
# carry qemu's -L.
set(CMAKE_CROSSCOMPILING_EMULATOR env;COLLIDE2D_NO_HUGE_PAGES=1;${COLLIDE2D_CROSS_QEMU};-L;${_sysroot})
