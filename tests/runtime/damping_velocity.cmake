# The demo models under both damping velocities (kernel/README, "Damping velocity"): each config
# model as it is (central, the default) and with damping_velocity = "lagged" written into its
# [model] table, run by ntn-run on El Centro, at its reference hash. The lagged hashes are those of
# the models before the key existed: the seed's S 3-4 form, bit for bit. -DRUN=ntn-run,
# -DCONFIG=config/, -DRECORD=the record, -DOUT=a folder.
file(MAKE_DIRECTORY ${OUT})
set(models frame3d portal_plastic portal_slip)
set(central_hashes 6e2293debe9ca748 621633f7c486646f 8f1fa49ac3259877)
set(lagged_hashes fe2a0f51b4edafe7 2fe81548b9c160e2 26a01166d648d2fe)
foreach(i RANGE 2)
  list(GET models ${i} model)
  file(READ ${CONFIG}/${model}.toml text)
  string(FIND "${text}" "\n[model]\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${model}.toml has no [model] line")
  endif()
  string(REPLACE "\n[model]\n" "\n[model]\ndamping_velocity = \"lagged\"\n" lagged "${text}")
  file(WRITE ${OUT}/${model}_lagged.toml "${lagged}")
  foreach(mode central lagged)
    if(mode STREQUAL "central")
      set(file ${CONFIG}/${model}.toml)
      list(GET central_hashes ${i} expected)
    else()
      set(file ${OUT}/${model}_lagged.toml)
      list(GET lagged_hashes ${i} expected)
    endif()
    execute_process(COMMAND ${RUN} ${file} --input ag_x=${RECORD} -q --out ${OUT}/${model}.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out}")
    if(NOT rc EQUAL 0 OR NOT CMAKE_MATCH_1 STREQUAL expected)
      message(FATAL_ERROR
              "${model} ${mode}: exit ${rc}, output hash '${CMAKE_MATCH_1}', the reference is "
              "${expected}\n${out}${err}")
    endif()
    message(STATUS "${model}, damping_velocity = \"${mode}\": output hash ${CMAKE_MATCH_1}")
  endforeach()
endforeach()
