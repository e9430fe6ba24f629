# tools/campaign/gate_replay.py replays the pipeline's output gates over frames.csv. Its self-check: on the
# named cases (acquisition, reacquisition after an eclipse and a slew, near-range tracking), with the shipped
# gate values, every scene's tracked and confidently wrong counts must equal the campaign's own. A gate
# changed in the pipeline but not in the replay fails here. Then tools/campaign/far_distance.py must read the
# same frames.csv (the 750 m approach case has far fixes) and print at least one size bin, and
# tools/campaign/wrong_origins.py must pass its self-test and read it too (the cases have no wrong frame).
# -DCAMPAIGN=<visnav-campaign> -DPYTHON=<python3> -DREPLAY=<gate_replay.py> -DFAR_DISTANCE=<far_distance.py>
# -DWRONG_ORIGINS=<wrong_origins.py> -DOUT=<dir>
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${CAMPAIGN} --case all --jobs 2 --frames --no-timing --quiet --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "visnav-campaign exited ${rc}:\n${out}\n${err}")
endif()
execute_process(COMMAND ${PYTHON} ${REPLAY} ${OUT}/frames.csv --check ${OUT}/scenes.csv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gate_replay.py --check exited ${rc}:\n${out}\n${err}")
endif()
execute_process(COMMAND ${PYTHON} ${FAR_DISTANCE} ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "\n +[0-9]+-[0-9inf]+ +[1-9][0-9]* ")
  message(FATAL_ERROR "far_distance.py exited ${rc} or printed no size bin:\n${out}\n${err}")
endif()
execute_process(COMMAND ${PYTHON} ${WRONG_ORIGINS} --self-test
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "wrong_origins.py --self-test exited ${rc}:\n${out}\n${err}")
endif()
execute_process(COMMAND ${PYTHON} ${WRONG_ORIGINS} ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "^wrong frames: 0\n")
  message(FATAL_ERROR "wrong_origins.py exited ${rc} or did not count the cases' 0 wrong frames:\n${out}\n${err}")
endif()
