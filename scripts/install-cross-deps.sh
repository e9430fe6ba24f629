#!/usr/bin/env bash
# Installs what the aarch64 cross build (preset `aarch64`, toolchains/aarch64-linux-gnu.cmake) needs on a
# Debian 12 x86-64 host, only the packages that are missing (no network needed when all are present):
# the cross compiler, qemu-user (runs the arm64 tests and replay), and the arm64 multiarch -dev packages of
# every library the build links. Run as root or with sudo available. The host packages of
# scripts/install-deps.sh are needed too (cmake, ninja, the host idlc, Eigen): this script calls it first.
# Never installs cyclonedds-tools:arm64: it replaces the host /usr/bin/idlc the cross build runs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
host_packages=(g++-aarch64-linux-gnu binutils-aarch64-linux-gnu qemu-user binfmt-support)
# The arm64 libraries the build links (find_package/pkg_check_modules in the CMakeLists.txt files): toml++,
# GoogleTest + GoogleMock, Google Benchmark, zlib (tools/png, tests), libcamera (drivers/libcamera), Cyclone DDS
# (fsw/telemetry); pkgconf:arm64 provides aarch64-linux-gnu-pkg-config. Eigen is header-only and
# arch-independent (the host libeigen3-dev serves both). linux-libc-dev:arm64 gives the V4L2 headers.
arm64_packages=(libtomlplusplus-dev libgtest-dev libgmock-dev libbenchmark-dev zlib1g-dev libcamera-dev
                cyclonedds-dev linux-libc-dev pkgconf)
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  echo "install-cross-deps: adding the arm64 architecture"
  "${sudo_cmd[@]}" dpkg --add-architecture arm64
fi
missing=()
for p in "${host_packages[@]}" "${arm64_packages[@]/%/:arm64}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-cross-deps: all $(( ${#host_packages[@]} + ${#arm64_packages[@]} )) packages present"
  exit 0
fi
echo "install-cross-deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
