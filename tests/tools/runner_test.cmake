# Runs ntn-run-frame3d twice on El Centro and checks what a user relies on. Under the sanitizers
# (SANITIZED) once: the repeat is Release's to check, the sanitizers' job is the run itself and
# the reference hash, and each El Centro run costs ~28 s there.
file(MAKE_DIRECTORY ${OUT})
set(runs a b)
if(SANITIZED)
  set(runs a)
endif()
foreach(run ${runs})
  execute_process(COMMAND ${RUNNER} --input ag_x=${RECORD} --out ${OUT}/${run}.csv
                          --summary-json ${OUT}/${run}.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out_${run} ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run ${run} exited ${rc}: ${err}")
  endif()
endforeach()
foreach(expected "peak drift" "peak base shear" "real-time factor" "dt = " "output hash")
  string(FIND "${out_a}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "summary lacks '${expected}':\n${out_a}")
  endif()
endforeach()
string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_a}")
set(hash_a ${CMAKE_MATCH_1})
# The repeat (not under the sanitizers): the same hash and the same CSV bytes.
if(NOT SANITIZED)
  string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_b}")
  if(NOT hash_a STREQUAL CMAKE_MATCH_1)
    message(FATAL_ERROR "two runs differ: ${hash_a} vs ${CMAKE_MATCH_1}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/a.csv ${OUT}/b.csv
                  RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "two runs wrote different CSV files")
  endif()
endif()
# The El Centro reference (README, tests/determinism): the default (--sampling step, the records
# at every kernel step) is the runner's input semantics before the loop library ran it, to the bit.
# Since damping_velocity = "central" became the default (kernel/README, "Damping velocity"),
# 6e2293debe9ca748; "lagged" keeps the hash before it, fe2a0f51b4edafe7 (damping_velocity.cmake in
# tests/runtime). That one came with the element order (kernel/README, "The model's element
# order": the nodes sum their elements' forces and masses in another order); before it
# b75556fff5aab1d0, and before the aligned elements (kernel/README, "Aligned elements pick")
# fa89d903ee8d9aa5.
if(NOT hash_a STREQUAL "6e2293debe9ca748")
  message(FATAL_ERROR "El Centro output hash ${hash_a}, the reference is 6e2293debe9ca748")
endif()
# 1559 samples x 0.02 s = 31.18 s at one row per 1 ms frame, plus the header row.
file(STRINGS ${OUT}/a.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 31181)
  message(FATAL_ERROR "expected 31181 CSV lines, found ${n}")
endif()
list(GET rows 0 header)
if(NOT header MATCHES "^time\\[s\\],roof_ux\\[m\\],")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif()
# --duration limits the run: 0.5 s at one row per 1 ms frame is 500 rows and the header.
execute_process(COMMAND ${RUNNER} --input ag_x=${RECORD} --duration 0.5 --out ${OUT}/short.csv
                RESULT_VARIABLE rc OUTPUT_QUIET)
file(STRINGS ${OUT}/short.csv short_rows)
list(LENGTH short_rows n)
if(NOT rc EQUAL 0 OR NOT n EQUAL 501)
  message(FATAL_ERROR "--duration 0.5: exit ${rc}, ${n} CSV lines (expected 501)")
endif()
# A missing record is a clear error with exit code 2, not a crash.
execute_process(COMMAND ${RUNNER} --input ag_x=${OUT}/missing.AT2 RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "cannot open")
  message(FATAL_ERROR "missing record: exit ${rc}, '${err}'")
endif()
# Units: a record in gal and one in m/s2 feed the input in g converted, and the
# summary says so (peaks: 3.719808 gal = 0.003793 g; 1 m/s2 = 0.102 g, %.4g as printed).
foreach(case "at2/units_gal.AT2|peak 0.003793 g, converted from gal"
             "csv/units_m_s2.csv|peak 0.102 g, converted from m/s2")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 file)
  list(GET case 1 expected)
  execute_process(COMMAND ${RUNNER} --input ag_x=${REGRESSIONS}/${file} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}" "${expected}" at)
  if(NOT rc EQUAL 0 OR at EQUAL -1)
    message(FATAL_ERROR "${file}: exit ${rc}, summary lacks '${expected}':\n${out}${err}")
  endif()
endforeach()
# A CSV whose time starts at -1 s (a pre-trigger segment) is played from its first row, and the
# summary says so (it was shifted silently); one without a unit is taken as the input's, and says
# so.
file(WRITE ${OUT}/pretrigger.csv "time[s],ag_x\n-1,0.01\n-0.99,0.02\n-0.98,0\n")
execute_process(COMMAND ${RUNNER} --input ag_x=${OUT}/pretrigger.csv RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
foreach(expected "file time -1 s played at t = 0" "the file states no unit: taken as g")
  string(FIND "${out}" "${expected}" at)
  if(NOT rc EQUAL 0 OR at EQUAL -1)
    message(FATAL_ERROR "pretrigger.csv: exit ${rc}, summary lacks '${expected}':\n${out}${err}")
  endif()
endforeach()
