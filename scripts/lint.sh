#!/usr/bin/env bash
# Static checks: clang-format (every tracked C++ file must be formatted), cppcheck and clang-tidy (.clang-tidy)
# over the project's own sources (fsw/, drivers/, tools/), clang-tidy with the release build's
# compile_commands.json.
#   scripts/lint.sh              all three (clang-tidy takes minutes on 2 cores)
#   scripts/lint.sh --format     clang-format only (seconds; CI runs it as the ctest `format_check`)
#   scripts/lint.sh --cppcheck   cppcheck only (seconds; CI runs it as the ctest `cppcheck`)
#   scripts/lint.sh --fix        rewrites every tracked C++ file with clang-format (the others only check)
# Exit status is non-zero when any check reports something.
set -uo pipefail
cd "$(dirname "$0")/.."
only=${1:-all}
case $only in all | --format | --cppcheck | --fix) ;; *) echo "usage: scripts/lint.sh [--format | --cppcheck | --fix]" >&2; exit 2 ;; esac
status=0
if [[ $only == --fix ]]; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
  echo "lint: clang-format -i over ${#files[@]} files"
  clang-format -i "${files[@]}"
  exit $?
fi
if [[ $only == all || $only == --format ]]; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
  echo "lint: clang-format over ${#files[@]} files"
  clang-format --dry-run --Werror "${files[@]}" || status=1
fi
mapfile -t sources < <(git ls-files 'fsw/*.cpp' 'drivers/*.cpp' 'tools/*.cpp')
if [[ $only == all || $only == --cppcheck ]]; then
  echo "lint: cppcheck over ${#sources[@]} sources"
  cppcheck --quiet --error-exitcode=1 --enable=warning,performance,portability --inline-suppr \
           --suppress=missingIncludeSystem --std=c++17 --language=c++ -j 2 \
           $(printf -- '-I%s ' fsw/*/include drivers/*/include tools/*/include) "${sources[@]}" || status=1
fi
if [[ $only == all ]]; then
  [ -f build/release/compile_commands.json ] || { cmake --preset release >/dev/null && cmake --build --preset release; }
  # clang does not know gcc's -fvect-cost-model (the far-range library's NEON tuning): a copy of the
  # compile database without it, or clang-tidy would skip those files with an error.
  tidy_db=$(mktemp -d)
  trap 'rm -rf "$tidy_db"' EXIT
  sed 's/ -fvect-cost-model=[a-z]*//g' build/release/compile_commands.json >"$tidy_db/compile_commands.json"
  echo "lint: clang-tidy over ${#sources[@]} sources"
  run-clang-tidy -quiet -p "$tidy_db" -j 2 "${sources[@]}" 2>&1 | grep -v "warnings generated" | \
    grep -E "error:|warning:" && status=1
fi
exit $status
