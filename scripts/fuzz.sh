#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, ASan + UBSan without recovery) in build/fuzz and runs
# each for SECONDS (default 60), JOBS at a time (default 2), from its seed corpus (tests/fuzz/corpus/<target>,
# copied into build/fuzz/corpus so the seeds stay as committed). Prints execs, coverage and findings per
# target; exits non-zero on any crash, leak, timeout or out-of-memory. Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
# FUZZ_BUILD_DIR overrides the build directory (e.g. a fresh one to time a cold build). Prints the time of the
# configure+build and of the runs. Each target compiles only the parsers it fuzzes (tests/fuzz/CMakeLists.txt).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
shift || true
jobs="${JOBS:-2}"
build="$(realpath -m "${FUZZ_BUILD_DIR:-$root/build/fuzz}")"
t0=$(date +%s)
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ missing (scripts/install-deps.sh installs it)" >&2; exit 2; }
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE= \
      -DCMAKE_C_FLAGS="-O1 -g" -DCMAKE_CXX_FLAGS="-O1 -g" -DVISNAV_BUILD_FUZZERS=ON -DVISNAV_BUILD_TESTS=OFF \
      -DVISNAV_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target fuzzers -j "$jobs" >/dev/null
t_build=$(( $(date +%s) - t0 ))
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in "$root"/tests/fuzz/corpus/*/; do targets+=("$(basename "$dir")"); done
fi
rm -rf "$build/artifacts" "$build/logs"
mkdir -p "$build/tmp" "$build/logs"
export TMPDIR="$build/tmp"  # the targets' scratch files (tests/fuzz/fuzz_util.hpp)
run_one() {
  local t="$1"
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: a loader must stay well under it.
  local rc=0
  "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t/" "$build/corpus/$t" "$root/tests/fuzz/corpus/$t" \
    >"$build/logs/$t.log" 2>&1 || rc=$?
  echo "$rc" >"$build/logs/$t.rc"
}
running=0
for t in "${targets[@]}"; do
  [ -x "$build/bin/fuzz_$t" ] || { echo "fuzz.sh: no target fuzz_$t" >&2; exit 2; }
  run_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
done
wait || true
failed=0
total=0
printf '%-16s %12s %8s %8s %9s  %s\n' target execs exec/s cov crashes result
for t in "${targets[@]}"; do
  log="$build/logs/$t.log"
  rc="$(cat "$build/logs/$t.rc" 2>/dev/null || echo 99)"
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1 || true)"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1 || true)"
  cov="$( (grep -o 'cov: [0-9]*' "$log" || true) | tail -1 | cut -d' ' -f2)"
  findings="$(find "$build/artifacts/$t" -type f 2>/dev/null | wc -l)"
  result=ok
  if [ "$rc" != 0 ] || [ "$findings" != 0 ]; then result="FAIL (exit $rc, see $log)"; failed=1; fi
  total=$((total + ${execs:-0}))
  printf '%-16s %12s %8s %8s %9s  %s\n' "$t" "${execs:-?}" "${rate:-?}" "${cov:-?}" "$findings" "$result"
done
echo "total execs: $total in ${seconds} s per target, ${jobs} at a time"
echo "fuzz.sh: configure+build ${t_build} s, runs $(( $(date +%s) - t0 - t_build )) s"
exit "$failed"
