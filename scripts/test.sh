#!/usr/bin/env bash
# The README's second command: build and run every test.
#  1. debug preset (warnings as errors, ASan + UBSan): every unit and integration test (not the accuracy
#     scenarios, nor the campaign target gates that fail today: label campaign_targets);
#  2. release preset (the flight flags): every test again, including the accuracy scenarios (synthetic
#     sequences rendered, replayed and scored against the issue's bounds) and the allocation counts with
#     malloc counted too (ASan owns malloc in the debug build);
#  3. the arm64 flight build (scripts/test-arm64.sh): cross build, unit tests under qemu-aarch64, and the
#     arm64 replay of approach_ci against the x86 one within the stated tolerance;
#  4. a short fuzz run (scripts/fuzz.sh 10: every parser's libFuzzer target 10 s from its corpus, two at a
#     time, clang ASan + UBSan in build/fuzz); any crash, leak or hang fails.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset debug >/dev/null
cmake --build --preset debug
ctest --preset debug -LE "accuracy|campaign_targets"
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release
scripts/test-arm64.sh
scripts/fuzz.sh 10
