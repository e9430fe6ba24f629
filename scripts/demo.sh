#!/usr/bin/env bash
# The README's first command: install what is missing, build the release preset, then run the main job as a
# bounded live demo with no hardware: visnavd (the 5 Hz flight program) on its built-in default camera, the
# synthetic renderer playing config/scenarios/approach.toml live (25 m -> 5 m), publishes DDS telemetry on the
# loopback interface; visnav-monitor, a second process, shows the live pose, mode and health as they arrive.
# It ends by itself after SECONDS (default 60) with both summaries; Ctrl-C ends it early, cleanly (both
# processes stop and summarise).
#
#   scripts/demo.sh [live [SECONDS]]     the live demo (default)
#   scripts/demo.sh accuracy [SCENARIO]  the paper's sec. IV-A experiment instead: render SCENARIO (default
#                                        approach, 2001 frames; recede = the bias test), replay it through the
#                                        flight pipeline, score it and plot errors vs distance (a few minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-live}
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
bin=build/release/bin

if [[ $mode == accuracy ]]; then
  scenario=${2:-approach}
  out=out/demo/$scenario
  mkdir -p "$out"
  "$bin/visnav-synth" --scenario "config/scenarios/$scenario.toml" --out "$out/sequence"
  "$bin/visnav-replay" --sequence "$out/sequence" --config config/visnav.toml --out "$out/replay.csv" \
    --overlay-dir "$out" --overlay-every 250
  "$bin/visnav-eval" --sequence "$out/sequence" --replay "$out/replay.csv" --plot "$out/errors.png" \
    --csv "$out/errors.csv"
  echo "demo: plot $out/errors.png, tracker overlays $out/overlay_*.png, per-frame pose $out/replay.csv"
  exit 0
fi
if [[ $mode != live ]]; then
  echo "usage: scripts/demo.sh [live [SECONDS]] | accuracy [SCENARIO]" >&2
  exit 2
fi

seconds=${2:-60}
out=out/demo/live
mkdir -p "$out"
export CYCLONEDDS_URI="file://$PWD/config/cyclonedds-loopback.xml"
# visnavd waits (bounded) for the monitor's readers, so the recording starts at frame 0; its key=value event
# lines go to a file (the monitor owns the terminal).
"$bin/visnavd" --config config/visnavd.toml --wait-subscribers 1 --wait-timeout 30 2>"$out/visnavd.log" &
daemon=$!
stop_daemon() { kill -TERM "$daemon" 2>/dev/null || true; }
trap stop_daemon EXIT INT TERM
monitor_status=0
"$bin/visnav-monitor" --config config/visnavd.toml --duration "$seconds" --csv "$out/monitor.csv" ||
  monitor_status=$?
stop_daemon
daemon_status=0
wait "$daemon" || daemon_status=$?
trap - EXIT INT TERM

echo
echo "visnavd events (all in $out/visnavd.log):"
grep -E 'event=(start|mode_transition|command|camera_lost|cycle_slip|stop|stop_timing) ' "$out/visnavd.log" |
  sed 's/^/  /' || true
echo "demo: visnavd exit $daemon_status, visnav-monitor exit $monitor_status; every sample recorded in" \
  "$out/monitor.csv (+ _far_range.csv, _health.csv)"
