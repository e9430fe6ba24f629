# Smoke test: visnav-synth renders 5 frames of approach_ci.toml and writes a complete sequence directory;
# exit codes of the shared table (README "Exit codes"): a scenario that does not load is 3, a target that
# leaves the image (the same approach ending at 0.5 m, checked with --dry-run) is 1.
# Invoked as: cmake -DSYNTH=<exe> -DSCENARIO=<toml> -DOUT=<dir> -P synth_smoke.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${SYNTH}" --scenario "${SCENARIO}" --out "${OUT}" --frames 5 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-synth failed with ${rc}")
endif()
foreach(f sequence.toml camera.toml model.toml frames.csv truth.csv frames/000000.pgm frames/000004.pgm)
  if(NOT EXISTS "${OUT}/${f}")
    message(FATAL_ERROR "missing ${OUT}/${f}")
  endif()
endforeach()
file(STRINGS "${OUT}/truth.csv" rows)
list(LENGTH rows n)
if(NOT n EQUAL 6)
  message(FATAL_ERROR "truth.csv has ${n} lines, expected header + 5")
endif()
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${SYNTH}" --scenario "${OUT}-no-such.toml" --out "${OUT}" RESULT_VARIABLE rc
                OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 3)
  message(FATAL_ERROR "visnav-synth on a missing scenario: exit ${rc}, expected 3")
endif()
get_filename_component(scenario_dir "${SCENARIO}" DIRECTORY)
file(READ "${SCENARIO}" text)
string(REGEX REPLACE "d_end_m = [0-9.]+" "d_end_m = 0.5" text "${text}")
# Relative paths in the scenario are the scenario folder's: the copy names them from there.
string(REPLACE "\"../" "\"${scenario_dir}/../" text "${text}")
set(close_scenario "${OUT}-close.toml")
file(WRITE "${close_scenario}" "${text}")
execute_process(COMMAND "${SYNTH}" --scenario "${close_scenario}" --out "${OUT}" --dry-run RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(REMOVE "${close_scenario}")
file(REMOVE_RECURSE "${OUT}")
if(NOT rc EQUAL 1 OR NOT out MATCHES "target outside the image in [1-9]")
  message(FATAL_ERROR "visnav-synth --dry-run ending at 0.5 m: exit ${rc}, expected 1: ${out}${err}")
endif()
