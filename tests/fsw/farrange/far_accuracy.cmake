# Far-range accuracy gate (fsw/farrange/README.md): render the calibration frames and the far_range_ci scenario, calibrate
# gamma once per method, run both methods and fail unless the robust (default) method meets the targets:
# direction error median < 0.1 deg, distance error median < 10 % (750 m -> 30 m, one calibration), right
# target on >= 95 % of all frames and of the frames with the clutter object in view. Invoked as:
#   cmake -DBIN=<bin dir> -DSCENARIOS=<config/scenarios> -DOUT=<dir> -P far_accuracy.cmake
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
foreach(step
    "${BIN}/visnav-synth;--scenario;${SCENARIOS}/far_calibration.toml;--out;${OUT}/calibration"
    "${BIN}/visnav-synth;--scenario;${SCENARIOS}/far_range_ci.toml;--out;${OUT}/seq"
    "${BIN}/visnav-far-eval;--sequence;${OUT}/seq;--calibration;${OUT}/calibration;--csv;${OUT}/far_eval.csv;--require-direction-median-deg;0.1;--require-distance-median-pct;10;--require-right-fraction;0.95;--require-clutter-right-fraction;0.95")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(GET step 0 exe)
    message(FATAL_ERROR "${exe} failed with ${rc}")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT}/seq" "${OUT}/calibration")
