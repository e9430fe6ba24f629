# One exit-code table for every binary (README.md "Exit codes", visnav::cli::kExit*): each ground tool is run
# on a usage error (2), on an input or config that is missing or invalid (3), and on a negative result where
# it has one (1). Invoked as:
#   cmake -DBIN=<dir with the binaries> -DSOURCE_DIR=<repo> -DOUT=<scratch dir> -P tool_exit_codes.cmake
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(failures "")
set(checks 0)

# expect(CODE NAME ARGS... [STDERR regex]): runs BIN/NAME ARGS, requires exit CODE; when the last two
# arguments are STDERR and a regex, stderr (or stdout, for a negative result) must match it.
function(expect code name)
  set(args ${ARGN})
  set(pattern "")
  list(LENGTH args n)
  if(n GREATER 1)
    math(EXPR before_last "${n} - 2")
    list(GET args ${before_last} marker)
    if(marker STREQUAL "STDERR")
      math(EXPR last "${n} - 1")
      list(GET args ${last} pattern)
      list(REMOVE_AT args ${before_last} ${last})
    endif()
  endif()
  execute_process(COMMAND "${BIN}/${name}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 60)
  math(EXPR count "${checks} + 1")
  set(checks ${count} PARENT_SCOPE)
  string(REPLACE ";" " " shown "${args}")
  if(NOT rc STREQUAL "${code}")
    set(failures "${failures}${name} ${shown}: exit ${rc}, expected ${code}\n  stderr: ${err}\n" PARENT_SCOPE)
  elseif(code GREATER 1 AND err STREQUAL "")
    set(failures "${failures}${name} ${shown}: exit ${rc} without a message on stderr\n" PARENT_SCOPE)
  elseif(NOT pattern STREQUAL "" AND NOT "${err}${out}" MATCHES "${pattern}")
    set(failures "${failures}${name} ${shown}: message does not match '${pattern}': ${err}${out}\n" PARENT_SCOPE)
  endif()
endfunction()

# Inputs: a 2-frame sequence with truth, its replay, and broken files.
execute_process(COMMAND "${BIN}/visnav-synth" --scenario "${SOURCE_DIR}/config/scenarios/approach_ci.toml"
                        --out "${OUT}/seq" --frames 2 RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-synth failed with ${rc}")
endif()
execute_process(COMMAND "${BIN}/visnav-replay" --sequence "${OUT}/seq" --out "${OUT}/replay.csv" --no-progress
                        --init-from-truth RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-replay failed with ${rc}")
endif()
file(STRINGS "${OUT}/replay.csv" replay_lines)
list(GET replay_lines 0 replay_header)
file(WRITE "${OUT}/empty_replay.csv" "${replay_header}\n")  # a replay that never produced a row
file(WRITE "${OUT}/garbage.csv" "frame,status\nnot,a replay\n")
file(WRITE "${OUT}/bad.toml" "[executive\nmajor_frame_hz = = 5\n")  # does not parse
file(WRITE "${OUT}/a.csv" "x,y\n1,2\n3,4\n")
file(WRITE "${OUT}/b.csv" "x,z\n1,2\n3,4\n")
file(WRITE "${OUT}/c.csv" "x,y\n1,2\n3,5\n")
file(WRITE "${OUT}/ragged.csv" "x,y\n1,2\n3\n")
file(WRITE "${OUT}/empty.csv" "")
set(missing "${OUT}/no-such-file")
set(unwritable "${OUT}/no-such-dir/out")

# visnav-eval
expect(2 visnav-eval --frobnicate 1)
expect(2 visnav-eval --sequence "${OUT}/seq")
expect(3 visnav-eval --sequence "${missing}" --replay "${OUT}/replay.csv" STDERR "no-such-file")
expect(3 visnav-eval --sequence "${OUT}/seq" --replay "${missing}" STDERR "no-such-file")
expect(3 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/garbage.csv" STDERR "garbage.csv")
expect(3 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/empty_replay.csv" STDERR "nothing to score")
expect(3 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/replay.csv" --far-range "${missing}")
expect(3 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/replay.csv" --plot "${unwritable}.png")
expect(0 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/replay.csv")
expect(1 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/replay.csv" --require-final-mode standby)

# visnav-campaign (plate/12 loses its track on frame 1: a tracked-fraction gate fails on 3 frames)
expect(2 visnav-campaign --frobnicate 1)
expect(2 visnav-campaign --runs 0)
expect(3 visnav-campaign --runs 1 --families plate --max-frames 3 --config "${OUT}/bad.toml" --out "${OUT}/camp"
       STDERR "bad.toml")
expect(3 visnav-campaign --runs 1 --families cao --max-frames 3 --model "${missing}" --out "${OUT}/camp"
       STDERR "no-such-file")
expect(3 visnav-campaign --runs 1 --families plate --max-frames 3 --out "${OUT}/a.csv/camp" STDERR "a.csv")
expect(0 visnav-campaign --runs 1 --seed 12 --families plate --max-frames 3 --quiet --out "${OUT}/camp")
expect(1 visnav-campaign --runs 1 --seed 12 --families plate --max-frames 3 --quiet --out "${OUT}/camp"
       --require-tracked-fraction 0.9 STDERR "GATE FAILED")

# visnav-edge-score
expect(0 visnav-edge-score --sequence "${OUT}/seq" --poses "${OUT}/replay.csv")
expect(0 visnav-edge-score --sequence "${OUT}/seq" --pose 0,0,20,0,0,180)
expect(2 visnav-edge-score --sequence "${OUT}/seq")
expect(2 visnav-edge-score --sequence "${OUT}/seq" --pose 0,0,20,0,0)
expect(2 visnav-edge-score --sequence "${OUT}/seq" --pose 0,0,20,0,0,180 --search-px 0)
expect(3 visnav-edge-score --sequence "${missing}" --pose 0,0,20,0,0,180 STDERR "no-such-file")
expect(3 visnav-edge-score --sequence "${OUT}/seq" --poses "${OUT}/garbage.csv" STDERR "garbage.csv")
# visnav-csvdiff
expect(0 visnav-csvdiff "${OUT}/a.csv" "${OUT}/a.csv")
expect(1 visnav-csvdiff "${OUT}/a.csv" "${OUT}/c.csv" STDERR "DIFFERENT")
expect(1 visnav-csvdiff "${OUT}/a.csv" "${OUT}/b.csv" STDERR "headers differ")
expect(2 visnav-csvdiff "${OUT}/a.csv")
expect(2 visnav-csvdiff "${OUT}/a.csv" "${OUT}/a.csv" --abs-tol x)
expect(3 visnav-csvdiff "${OUT}/a.csv" "${missing}" STDERR "no-such-file")
expect(3 visnav-csvdiff "${OUT}/a.csv" "${OUT}/ragged.csv" STDERR "number of cells")
expect(3 visnav-csvdiff "${OUT}/empty.csv" "${OUT}/a.csv" STDERR "empty")

# visnav-calibrate-gamma
expect(0 visnav-calibrate-gamma --pixels 16 --distance 750)
expect(2 visnav-calibrate-gamma --pixels 16)
expect(2 visnav-calibrate-gamma --pixels 16 --distance 750 --method best)
expect(3 visnav-calibrate-gamma --pixels 16 --distance 750 --config "${missing}" STDERR "no-such-file")
expect(3 visnav-calibrate-gamma --pixels 16 --distance 750 --config "${OUT}/bad.toml" STDERR "bad.toml")
expect(3 visnav-calibrate-gamma --sequence "${missing}" STDERR "no-such-file")
expect(3 visnav-calibrate-gamma --camera "${SOURCE_DIR}/config/cameras/vga_6mm.toml" --frame "${missing}.pgm"
       --distance 750 STDERR "no-such-file")
expect(3 visnav-calibrate-gamma --pixels 16 --distance 750 --out "${unwritable}.toml")

# visnav-far-eval
expect(2 visnav-far-eval --method best)
expect(2 visnav-far-eval --config "${SOURCE_DIR}/config/visnav.toml")
expect(3 visnav-far-eval --sequence "${missing}" STDERR "no-such-file")
expect(3 visnav-far-eval --sequence "${OUT}/seq" --config "${OUT}/bad.toml" STDERR "bad.toml")
expect(3 visnav-far-eval --sequence "${OUT}/seq" --calibration "${missing}" STDERR "no-such-file")

# visnav-jitter (no cycle runs in any of these)
expect(2 visnav-jitter --cycles 0)
expect(3 visnav-jitter --config "${missing}" STDERR "no-such-file")
expect(3 visnav-jitter --config "${OUT}/bad.toml" STDERR "bad.toml")

# visnav-monitor and visnav-command: the link options are read before DDS starts
expect(2 visnav-monitor --domain 999 --duration 0.1)
expect(3 visnav-monitor --config "${missing}" --duration 0.1 STDERR "no-such-file")
expect(3 visnav-monitor --config "${OUT}/bad.toml" --duration 0.1 STDERR "bad.toml")
expect(2 visnav-command standby --partition "bad partition*")
expect(3 visnav-command standby --config "${missing}" STDERR "no-such-file")
expect(3 visnav-command standby --config "${OUT}/bad.toml" STDERR "bad.toml")

# visnav-closedloop: the files are loaded before anything is flown
expect(2 visnav-closedloop --scenario warp)
expect(3 visnav-closedloop --scenario ci --config-dir "${missing}" STDERR "no-such-file")

# Numbers on the command line (visnav/cli/numbers.hpp): the whole argument, finite, and a count an integer;
# each of these was accepted before the shared parser (as NaN, infinity, a blank, or a count truncated,
# clamped or wrapped).
expect(2 visnav-csvdiff "${OUT}/a.csv" "${OUT}/a.csv" --abs-tol inf)
expect(2 visnav-csvdiff "${OUT}/a.csv" "${OUT}/a.csv" --column-tol "x_m=inf")
expect(2 visnav-eval --sequence "${OUT}/seq" --replay "${OUT}/replay.csv" --min-inside-fraction nan)
expect(2 visnav-far-eval --sequence "${OUT}/seq" --require-right-fraction nan)
expect(2 visnav-calibrate-gamma --pixels 16 --distance 750 --max-range inf)
expect(2 visnav-campaign --runs 1 --seed " -1")
expect(2 visnav-synth --scenario "${SOURCE_DIR}/config/scenarios/approach_ci.toml" --dry-run
       --frames 99999999999999999999)
expect(2 visnav-replay --sequence "${OUT}/seq" --out "${OUT}/r.csv" --max-frames " 3")
expect(2 visnav-edge-score --sequence "${OUT}/seq" --pose 0,0,20,0,0,180 --max-frames 1e3)
expect(2 visnav-jitter --priority 50.5)
expect(2 visnav-monitor --samples 1.5 --duration 0.1)
expect(2 visnav-command standby --id -4294967295)

if(failures)
  message(FATAL_ERROR "${failures}")
endif()
file(REMOVE_RECURSE "${OUT}")
message(STATUS "${checks} runs: every exit code as README.md \"Exit codes\" says")
