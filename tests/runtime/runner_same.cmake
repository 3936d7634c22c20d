# ntn-run MODEL.toml (run-time storage, no compile step) against the compiled runner of the same
# model: the same output hash and the same CSV bytes for the same options. -DRUN=ntn-run,
# -DCOMPILED=ntn-run-<model>, -DMODEL=the .toml, -DARGS=the options (a list), -DOUT=a folder,
# -DHASH=the reference hash or empty.
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${RUN} ${MODEL} ${ARGS} -q --out ${OUT}/runtime.csv
                RESULT_VARIABLE rc_r OUTPUT_VARIABLE out_r ERROR_VARIABLE err_r)
execute_process(COMMAND ${COMPILED} ${ARGS} -q --out ${OUT}/compiled.csv
                RESULT_VARIABLE rc_c OUTPUT_VARIABLE out_c ERROR_VARIABLE err_c)
if(NOT rc_r EQUAL rc_c)
  message(FATAL_ERROR "exit codes differ: ntn-run ${rc_r} (${err_r}), compiled ${rc_c} (${err_c})")
endif()
string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_r}")
set(hash_r "${CMAKE_MATCH_1}")
string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_c}")
set(hash_c "${CMAKE_MATCH_1}")
if(hash_r STREQUAL "" OR NOT hash_r STREQUAL hash_c)
  message(FATAL_ERROR "output hash: ntn-run '${hash_r}', compiled '${hash_c}'\n${out_r}${err_r}")
endif()
if(HASH AND NOT hash_r STREQUAL HASH)
  message(FATAL_ERROR "output hash ${hash_r}, the reference is ${HASH}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/runtime.csv ${OUT}/compiled.csv
                RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "ntn-run and the compiled runner wrote different CSV files")
endif()
message(STATUS "ntn-run and ${COMPILED}: output hash ${hash_r}, the same CSV")
