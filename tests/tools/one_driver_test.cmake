# One run driver: ntn-run-<model> and `ntn-hil-<model> run --clock virtual`
# run the same loop library, so for the same --sampling they print the same output hash and
# write the same CSV, byte for byte (the runner with --flags, which adds the loop's flags
# column). Each sampling must also change the response (else the option would do nothing), and
# each program's default must be the one its README names: ntn-run step, ntn-hil hold.
# 2 s of El Centro (2 000 frames of 9 steps: the first strong pulses, quick under ASan too);
# exact comparisons throughout: both programs must take the same steps to the same bits.
file(MAKE_DIRECTORY ${OUT})
set(common -q --input ag_x=${RECORD} --duration 2)

function(run_it name)  # run_it(NAME COMMAND...) -> hash_NAME in the parent scope
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: exit ${rc}: ${out}${err}")
  endif()
  string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out}")
  if(CMAKE_MATCH_1 STREQUAL "")
    message(FATAL_ERROR "${name}: no output hash in: ${out}")
  endif()
  set(hash_${name} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

foreach(sampling step hold interpolate)
  run_it(run_${sampling} ${RUNNER} ${common} --sampling ${sampling} --flags
         --out ${OUT}/run_${sampling}.csv)
  run_it(hil_${sampling} ${HIL} run --clock virtual ${common} --sampling ${sampling}
         --out ${OUT}/hil_${sampling}.csv)
  if(NOT hash_run_${sampling} STREQUAL hash_hil_${sampling})
    message(FATAL_ERROR "--sampling ${sampling}: ntn-run ${hash_run_${sampling}}, "
                        "ntn-hil ${hash_hil_${sampling}}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/run_${sampling}.csv
                          ${OUT}/hil_${sampling}.csv RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "--sampling ${sampling}: the two programs wrote different CSV files")
  endif()
  message(STATUS "--sampling ${sampling}: both ${hash_run_${sampling}}, CSV identical")
endforeach()
if(hash_run_step STREQUAL hash_run_hold OR hash_run_step STREQUAL hash_run_interpolate
   OR hash_run_hold STREQUAL hash_run_interpolate)
  message(FATAL_ERROR "two samplings gave the same response: step ${hash_run_step}, "
                      "hold ${hash_run_hold}, interpolate ${hash_run_interpolate}")
endif()

# The defaults, and the old spelling of interpolation in ntn-hil.
run_it(run_default ${RUNNER} ${common})
run_it(hil_default ${HIL} run --clock virtual ${common})
run_it(hil_interpolate_flag ${HIL} run --clock virtual ${common} --interpolate)
foreach(pair "run_default|run_step" "hil_default|hil_hold"
             "hil_interpolate_flag|hil_interpolate")
  string(REPLACE "|" ";" pair "${pair}")
  list(GET pair 0 a)
  list(GET pair 1 b)
  if(NOT hash_${a} STREQUAL hash_${b})
    message(FATAL_ERROR "${a} ${hash_${a}} is not ${b} ${hash_${b}}")
  endif()
endforeach()
# Without --flags the runner's CSV is the loop's without the flags column (its format before
# the two shared one run driver): the same header and rows up to the last comma.
file(STRINGS ${OUT}/hil_hold.csv with_flags)
execute_process(COMMAND ${RUNNER} ${common} --sampling hold --out ${OUT}/run_hold_plain.csv
                RESULT_VARIABLE rc OUTPUT_QUIET)
file(STRINGS ${OUT}/run_hold_plain.csv plain)
list(GET with_flags 0 head_flags)
list(GET plain 0 head_plain)
list(GET with_flags 1500 row_flags)
list(GET plain 1500 row_plain)
string(FIND "${row_flags}" "," last_comma REVERSE)
string(SUBSTRING "${row_flags}" 0 ${last_comma} row_flags_cut)
if(NOT rc EQUAL 0 OR NOT head_flags STREQUAL "${head_plain},flags"
   OR NOT row_flags_cut STREQUAL row_plain)
  message(FATAL_ERROR "ntn-run without --flags: exit ${rc}, '${head_plain}' / '${row_plain}' "
                      "against the loop's '${head_flags}' / '${row_flags}'")
endif()
file(REMOVE_RECURSE ${OUT})
