# visnav-replay's command line: bad values are exit 2 with a message naming the option, an input that does
# not load exit 3; a good run with
# --max-frames N writes exactly N rows. Invoked as:
#   cmake -DSYNTH=<exe> -DREPLAY=<exe> -DSCENARIO=<toml> -DOUT=<dir> -P replay_cli.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${SYNTH}" --scenario "${SCENARIO}" --out "${OUT}/seq" --frames 4 RESULT_VARIABLE rc
                OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-synth failed with ${rc}")
endif()
foreach(bad "--max-frames;0" "--max-frames;-2" "--max-frames;3x" "--overlay-every;" "--overlay-every;0"
            "--residual;plane" "--initial-pose;1,2,3" "--frobnicate;1")
  execute_process(COMMAND "${REPLAY}" --sequence "${OUT}/seq" --out "${OUT}/r.csv" --no-progress ${bad}
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  list(GET bad 0 option)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "visnav-replay ${bad}: exit ${rc}, expected 2")
  endif()
  string(FIND "${err}" "${option}" at)
  if(at LESS 0 AND NOT option STREQUAL "--overlay-every")  # a missing value prints the usage instead
    message(FATAL_ERROR "visnav-replay ${bad}: message does not name ${option}: ${err}")
  endif()
endforeach()
# An input that does not load is exit 3, as for visnavd and visnav-params (README "Exit codes").
execute_process(COMMAND "${REPLAY}" --sequence "${OUT}/seq" --out "${OUT}/r.csv" --no-progress
                        --config "${OUT}/no-such-config.toml" RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 3 OR NOT err MATCHES "no-such-config.toml")
  message(FATAL_ERROR "visnav-replay --config <missing>: exit ${rc}, expected 3 naming the file: ${err}")
endif()
execute_process(COMMAND "${REPLAY}" --sequence "${OUT}/no-such-sequence" --out "${OUT}/r.csv" --no-progress
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 3)
  message(FATAL_ERROR "visnav-replay --sequence <missing>: exit ${rc}, expected 3")
endif()
execute_process(COMMAND "${REPLAY}" --sequence "${OUT}/seq" --out "${OUT}/r.csv" --no-progress --max-frames 3
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-replay --max-frames 3 failed with ${rc}")
endif()
file(STRINGS "${OUT}/r.csv" rows)
list(LENGTH rows n)
if(NOT n EQUAL 4)
  message(FATAL_ERROR "replay CSV has ${n} lines, expected header + 3")
endif()
file(REMOVE_RECURSE "${OUT}")
