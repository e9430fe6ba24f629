# Accuracy gate (issue 2): render a scenario, replay it through the flight tracker, score it against truth.
# Fails when a frame is not tracked or fewer than MIN_INSIDE (default 0.995, the issue's bound for the paper
# scenarios) of frames have all six axes inside the 0.25 px worst-case envelope. Invoked as:
#   cmake -DBIN=<bin dir> -DSCENARIO=<toml> -DOUT=<dir> [-DRESIDUAL=vertex|point_to_line] [-DMIN_INSIDE=F]
#         -P accuracy_scenario.cmake
set(EXTRA "")
if(NOT MIN_INSIDE)
  set(MIN_INSIDE 0.995)
endif()
if(RESIDUAL)
  set(EXTRA "--residual;${RESIDUAL}")
endif()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
foreach(step
    "${BIN}/visnav-synth;--scenario;${SCENARIO};--out;${OUT}/seq"
    "${BIN}/visnav-replay;--sequence;${OUT}/seq;--out;${OUT}/replay.csv;--no-progress;${EXTRA}"
    "${BIN}/visnav-eval;--sequence;${OUT}/seq;--replay;${OUT}/replay.csv;--plot;${OUT}/errors.png;--require-tracked-all;--min-inside-fraction;${MIN_INSIDE};--inside-envelope-px;0.25")
  list(FILTER step EXCLUDE REGEX "^$")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(GET step 0 exe)
    message(FATAL_ERROR "${exe} failed with ${rc}")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT}/seq")
