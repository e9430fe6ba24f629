#!/usr/bin/env bash
# Prints the arm64 cost table: executed instructions per stage of the near-range and far-range steps at VGA
# (exact counts from a qemu-user TCG plugin), the estimated Cortex-A53 time and the share of the 200 ms cycle.
#   scripts/arm-cost.sh [visnav-arm-cost options: --frames N --ipc X --ipc-low X --clock-ghz G --cycle-ms T]
# Builds only what it needs in the aarch64 preset's directory (BUILD_DIR to override), 2 jobs at most.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build/aarch64}
scripts/install-cross-deps.sh >/dev/null
if [ ! -f "$build_dir/build.ninja" ]; then
  if [ "$build_dir" = build/aarch64 ]; then cmake --preset aarch64 >/dev/null
  else cmake -S . -B "$build_dir" -G Ninja --toolchain toolchains/aarch64-linux-gnu.cmake -DCMAKE_BUILD_TYPE=Release \
         -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DVISNAV_WERROR=ON >/dev/null; fi
fi
ninja -C "$build_dir" -j2 visnav-arm-cost insncount_plugin >/dev/null
qemu-aarch64 --version | head -1
exec qemu-aarch64 -plugin "$build_dir/lib/libinsncount.so" "$build_dir/bin/visnav-arm-cost" "$@"
