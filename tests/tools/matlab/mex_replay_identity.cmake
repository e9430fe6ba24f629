# The Octave MEX against visnav-replay (ctest mex_replay_identity): render a sequence, replay it with the
# flight pipeline (--no-timing), run it frame by frame through the MEX in Octave (test_visnav_mex.m), and
# require the two CSVs to be identical byte for byte. Invoked as:
#   cmake -DSYNTH=<exe> -DREPLAY=<exe> -DOCTAVE=<exe> -DMATLAB_DIR=<build>/matlab -DTEST_DIR=<this folder>
#         -DSCENARIO=<toml> -DCONFIG=<toml> -DOUT=<dir> [-DPRELOAD=libasan.so:libubsan.so] -P mex_replay_identity.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${SYNTH}" --scenario "${SCENARIO}" --out "${OUT}/seq" RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-synth failed with ${rc}")
endif()
execute_process(COMMAND "${REPLAY}" --sequence "${OUT}/seq" --out "${OUT}/replay.csv" --config "${CONFIG}"
                        --no-timing --no-progress
                RESULT_VARIABLE rc OUTPUT_VARIABLE replay_out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-replay failed with ${rc}")
endif()
message(STATUS "${replay_out}")
# --no-history: octave otherwise writes its history at exit (an error line where HOME is not writable).
# PRELOAD (sanitizer builds): libasan/libubsan go first, as ASan requires, since octave itself is not built
# with them; octave's own leaks are not this test's business (detect_leaks=0), libvisnav's are the gtests'.
set(launcher "")
if(PRELOAD)
  set(launcher ${CMAKE_COMMAND} -E env "LD_PRELOAD=${PRELOAD}" "ASAN_OPTIONS=detect_leaks=0")
endif()
execute_process(COMMAND ${launcher} "${OCTAVE}" --no-gui --no-window-system --norc --no-history --quiet --eval
                        "addpath('${MATLAB_DIR}'); addpath('${TEST_DIR}'); test_visnav_mex('${OUT}/seq', '${CONFIG}', '${OUT}/mex.csv')"
                RESULT_VARIABLE rc OUTPUT_VARIABLE octave_out ERROR_VARIABLE octave_err)
message(STATUS "${octave_out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "octave failed with ${rc}: ${octave_err}")
endif()
file(STRINGS "${OUT}/replay.csv" replay_rows)
file(STRINGS "${OUT}/mex.csv" mex_rows)
list(LENGTH replay_rows n_replay)
list(LENGTH mex_rows n_mex)
if(NOT n_replay EQUAL n_mex)
  message(FATAL_ERROR "visnav-replay wrote ${n_replay} lines, the MEX ${n_mex}")
endif()
if(n_replay LESS 100)
  message(FATAL_ERROR "only ${n_replay} lines: the sequence is too short to mean anything")
endif()
math(EXPR last "${n_replay} - 1")
foreach(i RANGE ${last})
  list(GET replay_rows ${i} a)
  list(GET mex_rows ${i} b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "line ${i} differs:\n  visnav-replay: ${a}\n  MEX:           ${b}")
  endif()
endforeach()
file(SHA256 "${OUT}/replay.csv" h1)
file(SHA256 "${OUT}/mex.csv" h2)
if(NOT h1 STREQUAL h2)
  message(FATAL_ERROR "the files differ (line ends?): ${h1} vs ${h2}")
endif()
message(STATUS "mex_replay_identity: ${n_replay} lines identical (sha256 ${h1})")
