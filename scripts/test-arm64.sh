#!/usr/bin/env bash
# arm64 CI step: the flight computer's build, tested under qemu-aarch64 on the x86-64 host.
#  1. installs what is missing (scripts/install-cross-deps.sh: cross g++, qemu-user, arm64 -dev packages);
#  2. configures the `aarch64-ci` preset (the `aarch64` preset's Cortex-A53 flags, release -O2, warnings
#     as errors, but no -g: GCC's debug info does not change the generated code and cost 20-28 % of the
#     compile) and builds what step 3 and 4 run (the executables its tests name, and visnav-replay);
#  3. runs the flight code's unit tests under qemu-aarch64 and the instruction-count table once (`ctest
#     --preset aarch64-ci`: labels unit and armcost, not ground; exclusions and reasons in
#     toolchains/README.md);
#  4. renders the approach_ci sequence with the x86 release visnav-synth, replays it with the arm64
#     visnav-replay under qemu-aarch64 and with the x86 visnav-replay (same sequence, both with the built-in
#     default parameters), and compares the two CSVs with visnav-csvdiff (tolerances below).
# X86_BUILD_DIR (default build/release, the release preset) holds the x86 tools; its preset is configured
# and the three tools built there when missing. Prints the time of each phase.
set -euo pipefail
cd "$(dirname "$0")/.."
x86_build=${X86_BUILD_DIR:-build/release}
t0=$(date +%s)
phase() { echo "test-arm64: $1 done at $(( $(date +%s) - t0 )) s"; }

scripts/install-cross-deps.sh
phase "install"
cmake --preset aarch64-ci >/dev/null
# Only what runs here: the gtest executables labelled unit but not ground (target
# flight_unit_test_executables: the flight code's; the ground tools' unit tests run in the debug preset;
# ctest lists a gtest executable's tests only after it is built), the executables the preset's other tests
# name (their commands and the tools passed to cmake -P checks), and visnav-replay for step 4. The integration tests, the daemon's, the
# benchmarks and most tools are not built. A test whose executable were missing fails.
mapfile -t arm_targets < <(ctest --preset aarch64-ci --show-only=json-v1 |
  grep -o "$PWD/build/aarch64-ci/bin/[A-Za-z0-9_.+-]*" | sed "s|^$PWD/build/aarch64-ci/||" | sort -u)
cmake --build --preset aarch64-ci --target flight_unit_test_executables "${arm_targets[@]}" bin/visnav-replay
phase "arm64 build (unit tests, ${#arm_targets[@]} more executables, visnav-replay)"
tests=$(ctest --preset aarch64-ci -N | sed -n 's/^Total Tests: //p')
[ "${tests:-0}" -ge 200 ] || { echo "test-arm64: the aarch64-ci preset lists ${tests:-no} tests, not hundreds" >&2; exit 1; }
ctest --preset aarch64-ci
phase "arm64 unit tests under qemu"

if [ ! -f "$x86_build/build.ninja" ]; then
  if [ "$x86_build" = build/release ]; then cmake --preset release >/dev/null
  else cmake -S . -B "$x86_build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
         -DVISNAV_WERROR=ON >/dev/null; fi
fi
ninja -C "$x86_build" -j2 visnav-synth visnav-replay visnav-csvdiff >/dev/null
out=build/aarch64-ci/replay_check
rm -rf "$out" && mkdir -p "$out"
"$x86_build/bin/visnav-synth" --scenario config/scenarios/approach_ci.toml --out "$out/sequence" >/dev/null
replay() {  # replay LOG COMMAND...: the progress bar goes to LOG, shown when the replay fails
  local log=$1
  shift
  "$@" 2>"$log" >>"$log" || { cat "$log"; exit 1; }
}
replay "$out/x86_64.log" "$x86_build/bin/visnav-replay" --sequence "$out/sequence" --out "$out/x86_64.csv"
replay "$out/aarch64.log" qemu-aarch64 build/aarch64-ci/bin/visnav-replay --sequence "$out/sequence" \
  --out "$out/aarch64.csv"
# Tolerance (README "ARM flight computer"): counts, flags and status exact (1e-9); the pose within a fifth of
# the tracker's own p95 error on the approach (x 2.1, y 1.4, z 21 mm; yaw 0.07, pitch 1.5, roll 1.7 deg),
# because the flat directions of the fit (distance, pitch/roll of a frontal plate) let the LM stop at
# slightly different points when fused multiply-adds round differently; quality and rms 1e-3 / 5e-3 px;
# covariance 1e-5 + 5 %; the filter's NIS 0.5 + 10 % (a diagnostic, printed to 6 digits: it follows the pose
# differences; the gate's verdict is in fault_bits, compared exactly). Timing columns (t_*) ignored.
"$x86_build/bin/visnav-csvdiff" "$out/x86_64.csv" "$out/aarch64.csv" --abs-tol 1e-9 --rel-tol 1e-9 \
  --ignore-prefix t_ --column-tol x_m=0.42e-3 --column-tol y_m=0.28e-3 --column-tol z_m=4.2e-3 \
  --column-tol yaw_deg=0.014 --column-tol pitch_deg=0.3 --column-tol roll_deg=0.34 --column-tol quality=1e-3 \
  --column-tol 'q*=3e-3' --column-tol rms_px=5e-3 --column-tol 'cov_*=1e-5:0.05' \
  --column-tol nis=0.5:0.1 | grep -v '^  cov_'
[ "${PIPESTATUS[0]}" -eq 0 ]
phase "arm64 vs x86 replay comparison"
echo "test-arm64: total $(( $(date +%s) - t0 )) s"
