# Record and replay of a yielding run: the demo portal (MODEL: config/portal_plastic.toml,
# in `ntn-hil run MODEL`), whose column bases yield under El Centro, run on the virtual clock with
# a log, replays bit-identical: the hinges' plastic history lives in the State the log's run rebuilds.
file(MAKE_DIRECTORY ${OUT})
set(log ${OUT}/run.ntnlog)
execute_process(COMMAND ${HIL} run ${MODEL} --clock virtual --input ag_x=${RECORD} --frames 31180
                        --record ${log}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run: exit ${rc}: ${out} ${err}")
endif()
if(NOT out MATCHES "plastic  2 of 4 plastic hinge directions yielded")
  message(FATAL_ERROR "the run's summary does not list the two yielded column bases: ${out}")
endif()
execute_process(COMMAND ${HIL} replay ${MODEL} ${log} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "bit-identical over 31180 frames")
  message(FATAL_ERROR "replay: exit ${rc}: ${out}")
endif()
file(REMOVE_RECURSE ${OUT})
