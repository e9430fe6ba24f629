#!/usr/bin/env bash
# The README's first command: install what is missing, build the release preset, and run the main job on its
# built-in default (no camera): the paper's sec. IV-A experiment. A synthetic plate approaches from 25 m to
# 5 m in 0.01 m steps; the flight tracker follows it; visnav-eval scores it and plots errors vs distance.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario=${1:-approach}
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
out=out/demo/$scenario
mkdir -p "$out"
bin=build/release/bin
"$bin/visnav-synth" --scenario "config/scenarios/$scenario.toml" --out "$out/sequence"
"$bin/visnav-replay" --sequence "$out/sequence" --config config/visnav.toml --out "$out/replay.csv" \
  --overlay-dir "$out" --overlay-every 250
"$bin/visnav-eval" --sequence "$out/sequence" --replay "$out/replay.csv" --plot "$out/errors.png" \
  --csv "$out/errors.csv"
echo "demo: plot $out/errors.png, tracker overlays $out/overlay_*.png, per-frame pose $out/replay.csv"
