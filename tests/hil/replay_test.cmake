file(MAKE_DIRECTORY ${OUT})
set(log ${OUT}/run.ntnlog)
# FRAMES frames (Release: 40 000, 40 s: El Centro's 31.2 s, then the free decay with the ground at
# rest; under the sanitizers 10 000, 10 s with the strong motion, each frame ~10x slower there)
# on the virtual clock, recorded. (It used to be 10^5 frames: the 69 s at rest added nothing but
# 30 s of the check's time under ASan.)
execute_process(COMMAND ${HIL} run --clock virtual --input ag_x=${RECORD} --frames ${FRAMES}
                        --record ${log} -q
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run: exit ${rc}: ${out} ${err}")
endif()
execute_process(COMMAND ${HIL} replay ${log} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "bit-identical over ${FRAMES} frames")
  message(FATAL_ERROR "replay: exit ${rc}: ${out}")
endif()

# Flip the lowest bit of frame 5000's input (t = 5 s, inside the record). Layout, format 2
# (hil_sim/include/ntn/hil/recorder.hpp): header 8 + 5 x 4 + 2 x 8 + 64 + 8 = 116 bytes; a frame
# of frame3d (1 input, 9 outputs) is 8 + 4 + 4 + 8 + 9 x 8 + 8 = 104 bytes; its input starts at
# 16. The frame's checksum no longer matches: the log is refused at that frame (exit 2).
# (tests/hil/record_e2e_test.cpp forges the checksum too and finds a changed output by replay.)
math(EXPR offset "116 + 5000 * 104 + 16")
file(READ ${log} byte OFFSET ${offset} LIMIT 1 HEX)
math(EXPR flipped "0x${byte} ^ 1" OUTPUT_FORMAT HEXADECIMAL)
string(SUBSTRING "${flipped}" 2 -1 flipped)
string(LENGTH "${flipped}" len)
if(len EQUAL 1)
  set(flipped "0${flipped}")
endif()
execute_process(COMMAND sh -c "printf '\\x${flipped}' | dd of=${log} bs=1 seek=${offset} conv=notrunc status=none"
                RESULT_VARIABLE rc)
execute_process(COMMAND ${HIL} replay ${log} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "frame 5000: checksum")
  message(FATAL_ERROR "a changed input bit at frame 5000 was not found there: exit ${rc}: ${out} ${err}")
endif()

# Real time against virtual time over the same 1500 frames (1.5 s of the record).
foreach(clock real virtual)
  execute_process(COMMAND ${HIL} run --clock ${clock} --input ag_x=${RECORD} --frames 1500 -q
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out_${clock})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${clock} clock: exit ${rc}")
  endif()
  string(REGEX MATCH "output hash ([0-9a-f]+)" _ "${out_${clock}}")
  set(hash_${clock} ${CMAKE_MATCH_1})
endforeach()
if(NOT hash_real STREQUAL hash_virtual OR hash_real STREQUAL "")
  message(FATAL_ERROR "real clock ${hash_real} != virtual clock ${hash_virtual}")
endif()

# Passed: the log and its directory go (a failure above keeps them for a look).
file(REMOVE_RECURSE ${OUT})
