# Cross-compiling for 64-bit ARM (aarch64) with Debian's cross compiler and the arm64 packages of
# the libraries (multiarch: /usr/lib/aarch64-linux-gnu). Used by scripts/cross-aarch64.sh.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
# Programs (cmake, the embedding script) are the build machine's; libraries and headers the target's.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
# Test binaries run under qemu-user where it is installed (gtest discovery, ctest).
find_program(PELAGE_QEMU_AARCH64 qemu-aarch64)
if(PELAGE_QEMU_AARCH64)
  # No -L: the arm64 packages' loader and C library (multiarch), not the cross toolchain's
  # (different glibc builds must not mix; see scripts/cross-aarch64.sh).
  set(CMAKE_CROSSCOMPILING_EMULATOR ${PELAGE_QEMU_AARCH64})
endif()
