# tools/campaign/gate_replay.py replays the pipeline's output gates over frames.csv. Its self-check: on the
# named cases (acquisition, reacquisition after an eclipse and a slew, near-range tracking), with the shipped
# gate values, every scene's tracked and confidently wrong counts must equal the campaign's own, also with a
# systematic line-end term given at its default (the sigmas rescaled from the cov_* columns). A gate
# changed in the pipeline but not in the replay fails here. Then tools/campaign/far_distance.py must read the
# same frames.csv (the 750 m approach case has far fixes) and print at least one size bin, and
# tools/campaign/wrong_origins.py must pass its self-test and read it too (the cases have no wrong frame), and
# so must tools/campaign/sigma_consistency.py (a row of near-range poses for the box cases).
# -DCAMPAIGN=<visnav-campaign> -DPYTHON=<python3> -DREPLAY=<gate_replay.py> -DFAR_DISTANCE=<far_distance.py>
# -DWRONG_ORIGINS=<wrong_origins.py> -DSIGMA_CONSISTENCY=<sigma_consistency.py> -DOUT=<dir>
# Runs the command after WHAT; fails unless it exits 0 and, when EXPECT is not empty, its output matches EXPECT.
function(run_expecting what expect)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} exited ${rc}:\n${out}\n${err}")
  endif()
  if(NOT expect STREQUAL "" AND NOT out MATCHES "${expect}")
    message(FATAL_ERROR "${what} printed nothing matching ${expect}:\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${OUT})
run_expecting("visnav-campaign" "" ${CAMPAIGN} --case all --jobs 2 --frames --no-timing --quiet --out ${OUT})
run_expecting("gate_replay.py --check" "" ${PYTHON} ${REPLAY} ${OUT}/frames.csv --check ${OUT}/scenes.csv)
# A bias term given at its default value rescales every candidate's sigma by the gain the run applied over
# the gain it recomputes from the cov_* columns: the same verdicts, or the recomputation is not the tracker's.
run_expecting("gate_replay.py --check, line-end bias given" "" ${PYTHON} ${REPLAY} ${OUT}/frames.csv
              --line-end-bias-px 0 --check ${OUT}/scenes.csv)
# The replay's model of narrow_break_reconfirms (stop 73; shipped since stop 74, when the run's kept_branch
# already carries it) runs on the same rows.
run_expecting("gate_replay.py --narrow-break-reconfirms" "^overall +tracked mean [01][.][0-9]+  confidently wrong 0 "
              ${PYTHON} ${REPLAY} ${OUT}/frames.csv --narrow-break-reconfirms)
# A size bin with at least one fix.
run_expecting("far_distance.py" "\n +[0-9]+-[0-9inf]+ +[1-9][0-9]* " ${PYTHON} ${FAR_DISTANCE} ${OUT})
run_expecting("wrong_origins.py --self-test" "" ${PYTHON} ${WRONG_ORIGINS} --self-test)
run_expecting("wrong_origins.py" "^wrong frames: 0\n" ${PYTHON} ${WRONG_ORIGINS} ${OUT})
run_expecting("sigma_consistency.py --self-test" "" ${PYTHON} ${SIGMA_CONSISTENCY} --self-test)
run_expecting("sigma_consistency.py" "\nbox +[0-9]+-[0-9inf]+ px +[1-9][0-9]* " ${PYTHON} ${SIGMA_CONSISTENCY} ${OUT})
