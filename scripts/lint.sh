#!/usr/bin/env bash
# Static checks: clang-format (every tracked C++ file must be formatted), cppcheck and clang-tidy (.clang-tidy)
# over the project's own sources, using the release build's compile_commands.json.
#   scripts/lint.sh            all three (clang-tidy takes minutes on 2 cores)
#   scripts/lint.sh --format   clang-format only (seconds; what CI runs as the `format_check` test)
# Exit status is non-zero when any check reports something.
set -uo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
status=0
echo "lint: clang-format over ${#files[@]} files"
clang-format --dry-run --Werror "${files[@]}" || status=1
[ "${1:-}" = "--format" ] && exit $status

[ -f build/release/compile_commands.json ] || { cmake --preset release >/dev/null && cmake --build --preset release; }
mapfile -t sources < <(git ls-files 'fsw/*.cpp' 'drivers/*.cpp' 'tools/*.cpp')
echo "lint: cppcheck over ${#sources[@]} sources"
cppcheck --quiet --error-exitcode=1 --enable=warning,performance,portability --inline-suppr \
         --suppress=missingIncludeSystem --std=c++17 --language=c++ -j 2 \
         $(printf -- '-I%s ' fsw/*/include drivers/*/include tools/*/include) "${sources[@]}" || status=1
echo "lint: clang-tidy over ${#sources[@]} sources"
run-clang-tidy -quiet -p build/release -j 2 "${sources[@]}" 2>&1 | grep -v "warnings generated" | \
  grep -E "error:|warning:" && status=1
exit $status
