#!/usr/bin/env bash
# Installs the Debian 12 packages visnav builds with, only those missing (no network needed when all are
# present). Run as root or with sudo available.
#   --kernel-cameras  only the optional group scripts/test-kernel-cameras.sh needs (qemu, busybox, v4l2-ctl, cam)
set -euo pipefail
if [ "${1:-}" = "--kernel-cameras" ]; then
  # The VM of the kernel-camera test: qemu under TCG, a busybox initramfs, vivid's controls (v4l2-ctl),
  # libcamera's `cam` and IPA modules (vimc's pipeline needs its IPA); make/gcc/xz build vimc out of tree.
  # The kernel itself is downloaded, never installed.
  packages=(qemu-system-x86 busybox-static v4l-utils libcamera-tools libcamera-ipa build-essential xz-utils)
else
  packages=(build-essential cmake ninja-build pkgconf libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev
            libtomlplusplus-dev libcamera-dev linux-libc-dev)
  packages+=(zlib1g-dev)                       # the PNG writer of the plots (tools/png) and the tests' reader
  packages+=(cyclonedds-dev cyclonedds-tools)  # DDS telemetry: Cyclone DDS C library and idlc (fsw/telemetry)
  packages+=(git clang-format cppcheck)        # static checks (scripts/lint.sh); CI runs format_check and cppcheck
  packages+=(clang libclang-rt-14-dev)         # fuzz targets (scripts/fuzz.sh): clang 14 with libFuzzer
  packages+=(help2man lintian)                 # man pages from --help at build time; the .deb's check
  packages+=(python3)                          # tools/campaign/gate_replay.py (ctest campaign_gate_replay)
  packages+=(systemd)                          # systemd-analyze: the unit's sandbox rating (ctest unit_security)
  packages+=(octave octave-dev)                # Octave MEX (tools/matlab): octave-cli; mkoctfile (octave-dev = liboctave-dev)
  packages+=(debootstrap)                      # scripts/test-package.sh: a clean Debian 12 root for the .deb
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
