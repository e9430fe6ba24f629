# Cross toolchain for the aarch64 flight computer (Debian 12 host: scripts/install-cross-deps.sh installs
# g++-aarch64-linux-gnu, qemu-user and the arm64 multiarch -dev packages). Compiler, sysroot and find rules
# only; the CPU flags live in cpu/<core>.cmake (VISNAV_TARGET_CPU, default cortex-a53). No absolute compiler
# paths: the cross compiler and qemu are found on PATH.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Debian multiarch: the arm64 -dev packages put their libraries and CMake/pkg-config files under
# /usr/lib/aarch64-linux-gnu and their headers under /usr/include (arch-specific ones under
# /usr/include/aarch64-linux-gnu); the cross libc lives in /usr/aarch64-linux-gnu.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)   # build tools (idlc, qemu, pkg-config) are host programs
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# Never pick up a host (x86-64) library or package config by accident.
set(CMAKE_IGNORE_PATH /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu/cmake
                      /usr/lib/x86_64-linux-gnu/pkgconfig)
# pkgconf:arm64 provides the cross pkg-config (searches only the arm64 .pc directories).
set(PKG_CONFIG_EXECUTABLE aarch64-linux-gnu-pkg-config CACHE FILEPATH "pkg-config for the arm64 packages")

# ctest and gtest_discover_tests run the arm64 binaries through qemu-user. Plain qemu-aarch64, no
# `-L /usr/aarch64-linux-gnu`: with -L the loader and libc versions mismatch and the first pthread_create
# spins forever (../shared/notes/platform.md); the arm64 loader of libc6:arm64 is at /lib.
find_program(VISNAV_QEMU_AARCH64 qemu-aarch64)
if(VISNAV_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${VISNAV_QEMU_AARCH64})
endif()

# Target core: cpu/${VISNAV_TARGET_CPU}.cmake (cortex-a53, cortex-a72).
set(VISNAV_TARGET_CPU cortex-a53 CACHE STRING "Target core: a file toolchains/cpu/<name>.cmake")
include(${CMAKE_CURRENT_LIST_DIR}/cpu/${VISNAV_TARGET_CPU}.cmake)
