# ntn-hil run MODEL.toml (run-time storage) against ntn-hil-<model> (compiled), on the virtual
# clock: the same output hash and CSV bytes; and a log recorded by the compiled program replays
# bit-identical in ntn-hil (and the other way round). -DHIL=ntn-hil, -DCOMPILED=ntn-hil-<model>,
# -DMODEL=the .toml, -DRECORD=an AT2, -DOUT=a folder.
file(MAKE_DIRECTORY ${OUT})
set(args --clock virtual --input ag_x=${RECORD} --duration 8 -q)
execute_process(COMMAND ${HIL} run ${MODEL} ${args} --out ${OUT}/runtime.csv
                        --record ${OUT}/runtime.log
                RESULT_VARIABLE rc_r OUTPUT_VARIABLE out_r ERROR_VARIABLE err_r)
execute_process(COMMAND ${COMPILED} run ${args} --out ${OUT}/compiled.csv
                        --record ${OUT}/compiled.log
                RESULT_VARIABLE rc_c OUTPUT_VARIABLE out_c ERROR_VARIABLE err_c)
if(NOT rc_r EQUAL 0 OR NOT rc_c EQUAL 0)
  message(FATAL_ERROR "exit codes: ntn-hil ${rc_r} (${err_r}), compiled ${rc_c} (${err_c})")
endif()
string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_r}")
set(hash_r "${CMAKE_MATCH_1}")
string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_c}")
if(hash_r STREQUAL "" OR NOT hash_r STREQUAL CMAKE_MATCH_1)
  message(FATAL_ERROR "output hash: ntn-hil '${hash_r}', compiled '${CMAKE_MATCH_1}'")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/runtime.csv ${OUT}/compiled.csv
                RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "ntn-hil and the compiled program wrote different CSV files")
endif()
# Each program replays the other's log bit for bit.
execute_process(COMMAND ${HIL} replay ${MODEL} ${OUT}/compiled.log RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "bit-identical")
  message(FATAL_ERROR "ntn-hil replay of the compiled log: exit ${rc}: ${out}${err}")
endif()
execute_process(COMMAND ${COMPILED} replay ${OUT}/runtime.log RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "bit-identical")
  message(FATAL_ERROR "compiled replay of ntn-hil's log: exit ${rc}: ${out}${err}")
endif()
# A model file with an error: file:line:column and exit 1, nothing run.
file(READ ${MODEL} text)
string(REPLACE "[model]\n" "[model]\nnot_a_key = 1\n" text "${text}")
file(WRITE ${OUT}/bad.toml "${text}")
execute_process(COMMAND ${HIL} run ${OUT}/bad.toml ${args} RESULT_VARIABLE rc
                ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 1 OR NOT err MATCHES "bad.toml:[0-9]+:[0-9]+: error: .*not_a_key")
  message(FATAL_ERROR "bad model: exit ${rc}, '${err}'")
endif()
message(STATUS "ntn-hil and ${COMPILED}: output hash ${hash_r}, the same CSV, logs cross-replay")
