# ntn_fuzz_large_seeds(DIR): writes one seed of about 1.1 MB per fuzz target into DIR/<target>/,
# so that the fuzzers start from (and mutate) inputs of the size real files reach: a model of a
# few thousand members, a long record, a long CSV. Made at configure time in the build tree (not
# committed: they are generated from a few lines each); string(REPEAT) and a short loop keep it
# fast.
function(ntn_fuzz_large_seeds dir)
  # modelc: a valid cantilever chain of 9 000 members (distinct ids; fixed at node 0).
  set(toml "[model]\nname = \"large_chain\"\ndt = \"auto\"\nframe_rate = 1000.0\n\n"
           "[[materials]]\nid = \"S\"\nE = 210e9\nG = 81e9\nrho = 7850.0\n\n"
           "[[sections]]\nid = \"P\"\nA = 1e-3\nIy = 1e-6\nIz = 1e-6\nJ = 2e-6\n\n")
  string(JOIN "" toml ${toml})
  set(n 9000)
  foreach(i RANGE 0 ${n})
    string(APPEND toml "[[nodes]]\nid = ${i}\nxyz = [${i}.0, 0.0, 0.0]\n\n")
  endforeach()
  foreach(i RANGE 1 ${n})
    math(EXPR j "${i} - 1")
    string(APPEND toml "[[members]]\nid = \"m${i}\"\nnodes = [${j}, ${i}]\n"
                       "material = \"S\"\nsection = \"P\"\n\n")
  endforeach()
  string(APPEND toml "[[supports]]\nnode = 0\nfix = \"all\"\n")
  file(WRITE ${dir}/modelc/large_chain.toml "${toml}")

  # at2: a PEER header and 110 000 values in 8F10 (about 1.1 MB).
  string(REPEAT "   0.00630  -0.00364   0.00099   0.00428  -0.00758   0.01087   0.00682   0.00277\n"
         13750 values)
  file(WRITE ${dir}/at2/large.AT2
       "PEER NGA STRONG MOTION DATABASE RECORD\nLARGE SEED, FUZZ\n"
       "ACCELERATION TIME SERIES IN UNITS OF G\n"
       "NPTS=110000, DT= .0050 SEC\n${values}")

  # csv: a header and 52 000 rows of three channels, time increasing by 0.005 s (0 to 260 s).
  # A block of 400 rows spans 2 s; its seconds are placeholders filled in per block.
  set(block "")
  foreach(i RANGE 0 399)
    math(EXPR ms "${i} * 5")
    math(EXPR frac "${ms} % 1000 + 1000")  # 1000..1999: drop the leading 1 for three digits
    string(SUBSTRING "${frac}" 1 3 frac)
    if(ms LESS 1000)
      string(APPEND block "@A@.${frac},0.0123,-0.0045\n")
    else()
      string(APPEND block "@B@.${frac},0.0123,-0.0045\n")
    endif()
  endforeach()
  set(csv "time[s],ag_x[g],ag_y[g]\n")
  foreach(b RANGE 0 129)
    math(EXPR a "2 * ${b}")
    math(EXPR c "2 * ${b} + 1")
    string(REPLACE "@A@" "${a}" rows "${block}")
    string(REPLACE "@B@" "${c}" rows "${rows}")
    string(APPEND csv "${rows}")
  endforeach()
  file(WRITE ${dir}/csv/large.csv "${csv}")

  # packet: datagrams are small by nature (at most kMaxPacketBytes); no large seed.
endfunction()
