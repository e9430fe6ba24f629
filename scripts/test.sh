#!/usr/bin/env bash
# The README's second command: build and run every test.
#  1. debug preset (warnings as errors, ASan + UBSan): every unit and integration test (not the accuracy
#     scenarios, nor the campaign target gates that fail today: label campaign_targets);
#  2. release preset (the flight flags): every test but the unit ones, including the accuracy scenarios
#     (synthetic sequences rendered, replayed and scored against the issue's bounds) and the integration
#     tests' allocation counts with malloc counted too (ASan owns malloc in the debug build). The unit tests
#     are not built a third time (VISNAV_UNIT_TESTS=OFF): they ran under the sanitizers in step 1 and run at
#     the flight flags, malloc counted, under qemu in step 3 (a cold release build here: 752 -> 490 s);
#  3. the arm64 flight build (scripts/test-arm64.sh): cross build, the flight code's unit tests under
#     qemu-aarch64 (not the ground tools': label ground), and the arm64 replay of approach_ci against the
#     x86 one within the stated tolerance;
#  4. a short fuzz run (scripts/fuzz.sh 10: every parser's libFuzzer target 10 s from its corpus, two at a
#     time, clang ASan + UBSan in build/fuzz); any crash, leak or hang fails.
# Each test executable is compiled as one unit (VISNAV_UNITY_TESTS; the builds here are cold ones). Each
# step's wall time is printed as it ends (the CI budget is 45 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
step() {  # step NAME COMMAND...: runs it, then prints how long it took
  local name="$1" start=$SECONDS
  shift
  "$@"
  echo "test.sh: step '$name' took $((SECONDS - start)) s (total $SECONDS s)"
}
step install-deps scripts/install-deps.sh
cmake --preset debug -DVISNAV_UNITY_TESTS=ON >/dev/null
step debug-build cmake --build --preset debug
step debug-tests ctest --preset debug -LE "accuracy|campaign_targets"
cmake --preset release -DVISNAV_UNIT_TESTS=OFF -DVISNAV_UNITY_TESTS=ON >/dev/null
step release-build cmake --build --preset release
step release-tests ctest --preset release
step arm64 scripts/test-arm64.sh
step fuzz scripts/fuzz.sh 10
