#!/usr/bin/env bash
# ctest package_lintian (fixture visnav_debs): lintian on every package package_deb_contents built (.deb and
# the -dbgsym .ddeb); any error or warning fails. Info, pedantic and experimental tags are printed, not counted
# (lintian's default display level shows errors, warnings and info).
# usage: lintian.sh PACKAGE_DIR
set -euo pipefail
shopt -s nullglob
packages=("$1"/*.deb "$1"/*.ddeb)
if [ ${#packages[@]} -lt 3 ]; then
  echo "lintian.sh: fewer than 3 packages in $1 (run package_deb_contents first)" >&2
  exit 1
fi
out=$(lintian --no-cfg --display-level '>=info' "${packages[@]}" 2>&1) || true
[ -n "$out" ] && echo "$out"
errors=$(grep -c '^E: ' <<<"$out" || true)
warnings=$(grep -c '^W: ' <<<"$out" || true)
echo "lintian: ${#packages[@]} packages ($(cd "$1" && echo *.deb *.ddeb)): $errors errors, $warnings warnings"
[ "$errors" -eq 0 ] && [ "$warnings" -eq 0 ]
