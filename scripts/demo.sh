#!/usr/bin/env bash
# The README's first command: install what is missing, build the release preset, then run the main job as a
# bounded live demo with no hardware: visnavd (the 5 Hz flight program) on its built-in default camera, the
# synthetic renderer playing config/scenarios/full_approach_ci.toml live (the plate from 750 m to 5 m: far
# range, acquisition, near range), publishes DDS telemetry on the loopback interface; visnav-monitor, a second
# process, shows the live pose, mode and health as they arrive. It ends by itself at the end of the approach
# (40 s) or after SECONDS (default 60) with both summaries; Ctrl-C ends it early, cleanly (both processes stop
# and summarise). Then the recording is scored against the scenario's truth (visnav-synth renders the same
# frames, bit for bit) and plotted: errors vs distance with the paper's envelopes (fig. 6), far-range direction
# and distance errors, and the mode timeline, in out/demo/live/errors.png.
#
#   scripts/demo.sh [live [SECONDS]]     the live demo (default)
#   scripts/demo.sh accuracy [SCENARIO]  the paper's sec. IV-A experiment instead: render SCENARIO (default
#                                        approach, 2001 frames; recede = the bias test), replay it through the
#                                        flight pipeline from the first truth pose (as the paper's experiment
#                                        starts: tracking only), score it and plot errors vs distance (30 s)
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
  "$bin/visnav-replay" --sequence "$out/sequence" --config config/visnav.toml --init-from-truth --out "$out/replay.csv" \
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
# visnavd waits (bounded) for the monitor's readers and their ready file, so the recording starts at frame 0. It stops by itself
# at the end of the approach (198 frames, 40 s) or after SECONDS. Its key=value event lines go to a file,
# because the monitor's live view owns the terminal.
rm -f "$out/monitor.ready"
"$bin/visnavd" --config config/visnavd.toml --cycles $((seconds * 5)) --wait-subscribers 1 --wait-timeout 30 \
  --wait-file "$out/monitor.ready" 2>"$out/visnavd.log" &
daemon=$!
"$bin/visnav-monitor" --config config/visnavd.toml --duration $((seconds + 30)) --csv "$out/monitor.csv" \
  --ready-file "$out/monitor.ready" &
monitor=$!
# Ctrl-C reaches both processes (each stops cleanly and prints its summary); TERM is passed on as well.
trap 'kill -TERM "$daemon" "$monitor" 2>/dev/null || true' INT TERM EXIT
daemon_status=0
while kill -0 "$daemon" 2>/dev/null; do wait "$daemon" || daemon_status=$?; done
kill -INT "$monitor" 2>/dev/null || true  # the daemon is done: the monitor prints its summary and ends
monitor_status=0
while kill -0 "$monitor" 2>/dev/null; do wait "$monitor" || monitor_status=$?; done
trap - INT TERM EXIT

echo
echo "visnavd events (all in $out/visnavd.log):"
grep -E 'event=(start|mode_transition|command|camera_lost|cycle_slip|stop|stop_timing) ' "$out/visnavd.log" |
  sed 's/^/  /' || true
echo "demo: visnavd exit $daemon_status, visnav-monitor exit $monitor_status; every sample recorded in" \
  "$out/monitor.csv (+ _far_range.csv, _health.csv)"

# Score what the monitor recorded. The truth is the scenario's: visnav-synth writes the frames the synthetic
# camera rendered live (same renderer, same seeds) with their truth poses. The plate looks the same turned
# 180 deg about its normal (z180).
[[ $daemon_status == 0 && $monitor_status == 0 ]] || exit 1
"$bin/visnav-synth" --scenario config/scenarios/full_approach_ci.toml --out "$out/sequence" >/dev/null
echo
"$bin/visnav-eval" --sequence "$out/sequence" --replay "$out/monitor.csv" --far-range "$out/monitor_far_range.csv" \
  --symmetry z180 --plot "$out/errors.png"
echo "demo: errors vs distance, far-range errors and the mode timeline of this run in $out/errors.png"
