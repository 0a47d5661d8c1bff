# `vplkit sweep --shard K/N` and `vplkit sweep merge`: a sweep run in 3 shards and merged has the
# unsharded run's rows in its order with exactly its quality columns; the merge refuses a missing
# shard, a shard given twice and a folder of another sweep, and warns when the shards ran on
# different machines. The reference's noise: a Light Wave sweep against a 64-sample Monte Carlo
# reference reports the noise's share and warns about it on stderr and in sweep.md. `vplkit
# compare` reports the same given a second reference. Seven sweeps: the slow tier.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")
cmake_policy(SET CMP0007 NEW)

# The rows of a CSV (no quoted cells in these sweeps) as lines.
function(read_rows csv variable)
  file(STRINGS "${csv}" lines)
  set(${variable} "${lines}" PARENT_SCOPE)
endfunction()

# The row without its timing columns (they differ from run to run; so do the Pareto front and
# the ties, which read the times): the cells of every other column, joined by '|'.
function(quality_cells header row variable)
  string(REPLACE "," ";" names "${header}")
  string(REPLACE "," ";" cells "${row}")
  set(kept "")
  list(LENGTH names count)
  math(EXPR last "${count} - 1")
  foreach(i RANGE ${last})
    list(GET names ${i} name)
    list(GET cells ${i} value)
    if(name MATCHES "^frame_ms|_ms$|^(timing_rounds|noise_met|timing|machine|pareto|tie|rank)$")
      continue()
    endif()
    list(APPEND kept "${name}=${value}")
  endforeach()
  string(JOIN "|" joined ${kept})
  set(${variable} "${joined}" PARENT_SCOPE)
endfunction()

# Two scenes x 3 radii x 2 seeds against the brute force: 6 rows.
set(grid sweep --technique rsm-radial --scene cornell-box --scene occluder --size 24 --rsm-size 32 --repeat 2 --min-rounds 1 --vary radius=0.125,0.25,0.5
         --reference rsm-brute-force --seeds 2)
expect_success("the unsharded sweep" "wrote .*sweep\\.csv" "${VPLKIT}" ${grid} --out "${WORK}/whole")
foreach(k 1 2 3)
  expect_success("shard ${k}/3 measures its 2 rows" "shard ${k}/3: 2 row\\(s\\) to measure.*wrote .*sweep\\.csv" "${VPLKIT}" ${grid} --shard ${k}/3 --out "${WORK}/shard${k}")
endforeach()
expect_success("the 3 shards merged" "sweep merge: 6 row\\(s\\) of 3 shard\\(s\\).*wrote .*sweep\\.csv.*wrote .*sweep\\.md"
               "${VPLKIT}" sweep merge "${WORK}/shard3" "${WORK}/shard1" "${WORK}/shard2" --out "${WORK}/merged")
read_rows("${WORK}/whole/sweep.csv" whole)
read_rows("${WORK}/merged/sweep.csv" merged)
list(LENGTH whole whole_count)
list(LENGTH merged merged_count)
list(GET whole 0 whole_header)
list(GET merged 0 merged_header)
expect_true("merged: the unsharded run's columns and 6 rows (${merged_count} lines)" whole_header STREQUAL merged_header AND merged_count EQUAL 7 AND whole_count EQUAL 7)
foreach(i RANGE 1 6)
  list(GET whole ${i} a)
  list(GET merged ${i} b)
  quality_cells("${whole_header}" "${a}" qa)
  quality_cells("${merged_header}" "${b}" qb)
  expect_true("merged row ${i}: the unsharded row's quality columns, exactly" qa STREQUAL qb AND qa MATCHES "rel_rmse=[0-9]" AND qa MATCHES "rel_rmse_seed2=[0-9]")
endforeach()
file(READ "${WORK}/merged/sweep.md" md)
expect_true("the merged sweep.md has both scenes and no shard line" md MATCHES "## cornell-box" AND md MATCHES "## occluder" AND NOT md MATCHES "Shard [0-9]")
file(READ "${WORK}/shard2/sweep.md" md)
expect_true("a shard's sweep.md says it is one" md MATCHES "Shard 2 of 3")

# The merge refuses what is not one whole sweep.
expect_failure("a missing shard" "shard 3/3 is missing" "${WORK}/m1/sweep.csv" "${VPLKIT}" sweep merge "${WORK}/shard1" "${WORK}/shard2" --out "${WORK}/m1")
expect_failure("a shard given twice" "shard 1/3 is given twice" "${WORK}/m2/sweep.csv"
               "${VPLKIT}" sweep merge "${WORK}/shard1" "${WORK}/shard1" "${WORK}/shard2" --out "${WORK}/m2")
expect_failure("an unsharded run with shards" "is shard 1/1, .* one of 3: shards of one sweep split it the same number of ways" "${WORK}/m3/sweep.csv"
               "${VPLKIT}" sweep merge "${WORK}/shard1" "${WORK}/whole" --out "${WORK}/m3")
expect_failure("a folder without a record" "holds no sweep-shard.txt" "${WORK}/m4" "${VPLKIT}" sweep merge "${WORK}" --out "${WORK}/m4")
expect_failure("--shard out of range" "--shard 4/3: expected K/N" "${WORK}/bad" "${VPLKIT}" ${grid} --shard 4/3 --out "${WORK}/bad")
expect_failure("--shard without N" "--shard 2: expected K/N" "${WORK}/bad" "${VPLKIT}" ${grid} --shard 2 --out "${WORK}/bad")

# Shards from two machines: a copy of shard 2 whose rows say another host. The merge warns on
# stderr and in sweep.md, and keeps each row's machine.
file(COPY "${WORK}/shard1" "${WORK}/shard2" "${WORK}/shard3" DESTINATION "${WORK}/other")
file(READ "${WORK}/other/shard2/sweep.csv" csv)
string(REGEX REPLACE ",(wall clock|timer queries),[^,]*," ",\\1,another-host: some GPU," csv "${csv}")
file(WRITE "${WORK}/other/shard2/sweep.csv" "${csv}")
execute_process(COMMAND "${VPLKIT}" sweep merge "${WORK}/other/shard1" "${WORK}/other/shard2" "${WORK}/other/shard3" --out "${WORK}/mixed"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(READ "${WORK}/mixed/sweep.md" md)
file(READ "${WORK}/mixed/sweep.csv" csv)
expect_true("shards of two machines: exit 0, a warning on stderr (${code}: ${err})" code EQUAL 0 AND err MATCHES "warning: the rows were timed on 2 machines")
expect_true("shards of two machines: sweep.md warns, the CSV keeps each row's machine" md MATCHES "Warning.*timed on 2 machines" AND csv MATCHES "another-host: some GPU")

# The reference's noise: Light Wave against a 64-sample Monte Carlo reference.
execute_process(COMMAND "${VPLKIT}" sweep --technique lightwave-accurate --scene cornell-box --size 48x27 --repeat 2 --min-rounds 1 --vary shadow-maps=1,5
                        --reference monte-carlo --reference-samples 64 --out "${WORK}/noise"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_true("a Light Wave sweep against 64 Monte Carlo samples warns on stderr, naming --reference-samples (${code}: ${err})"
            code EQUAL 0 AND err MATCHES "reference's own noise is more than 10 % of the error .*raise --reference-samples")
read_rows("${WORK}/noise/sweep.csv" rows)
list(GET rows 0 header)
list(GET rows 1 row)
string(REPLACE "," ";" names "${header}")
string(REPLACE "," ";" cells "${row}")
foreach(column rel_rmse rel_rmse_corrected rel_rmse_ref_se ref_noise ref_noise_share similarity_ref_se)
  list(FIND names ${column} index)
  set(${column} "")
  if(index GREATER -1)
    list(GET cells ${index} ${column})
  endif()
endforeach()
expect_true("the noise columns: ref_noise ${ref_noise} > 0, the share ${ref_noise_share} > 0.1, corrected ${rel_rmse_corrected} < raw ${rel_rmse}, standard errors"
            ref_noise GREATER 0 AND ref_noise_share GREATER 0.1 AND rel_rmse_corrected LESS rel_rmse AND rel_rmse_ref_se GREATER 0
            AND similarity_ref_se MATCHES "^[0-9]")
expect_failure("a folder of another sweep" "holds a shard of another sweep" "${WORK}/m5" "${VPLKIT}" sweep merge "${WORK}/whole" "${WORK}/noise" --out "${WORK}/m5")
file(READ "${WORK}/noise/sweep.md" md)
expect_true("sweep.md warns and shows the noise's share" md MATCHES "\\*\\*Warning\\*\\*: the reference's own noise .*--reference-samples" AND md MATCHES "reference noise \\(% of rel_rmse\\)")
# 4x the samples: half the noise (the estimate's standard error falls as 1/sqrt(samples)).
expect_success("the same against 256 samples" "wrote .*sweep\\.csv" "${VPLKIT}" sweep --technique lightwave-accurate --scene cornell-box --size 48x27 --repeat 2
               --min-rounds 1 --vary shadow-maps=1,5 --reference monte-carlo --reference-samples 256 --out "${WORK}/quieter")
read_rows("${WORK}/quieter/sweep.csv" rows)
list(GET rows 1 row)
string(REPLACE "," ";" cells "${row}")
list(FIND names ref_noise index)
list(GET cells ${index} quieter_noise)
# Half, within 20 % (the noise is itself estimated from two references of ~1300 pixels).
execute_process(COMMAND awk "BEGIN { r = ${quieter_noise} / ${ref_noise}; print (r > 0.4 && r < 0.6) ? \"yes \" r : \"no \" r }" OUTPUT_VARIABLE halved)
expect_true("4x the samples halves ref_noise (${ref_noise} -> ${quieter_noise}: ${halved})" halved MATCHES "^yes")

# compare, given a second reference: a third reference against the first has only the
# references' noise for an error, so about sqrt(2) x the noise (a share near 71 %), and warns.
foreach(seed 1 2 3)
  expect_success("a Monte Carlo reference of seed ${seed}" "wrote" "${VPLKIT}" reference --method monte-carlo --scene cornell-box --size 48x27 --samples 64
                 --reference-seed ${seed} --out "${WORK}/r${seed}.pfm")
endforeach()
execute_process(COMMAND "${VPLKIT}" compare "${WORK}/r3.pfm" "${WORK}/r1.pfm" --second-reference "${WORK}/r2.pfm" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "noise / relative RMSE \\(%\\) \\| ([0-9.]+)" found "${out}")
set(share "${CMAKE_MATCH_1}")
expect_true("compare: the noise is ${share} % of a reference-against-reference error (60 to 82), a warning (${code}: ${err})"
            code EQUAL 0 AND share GREATER 60 AND share LESS 82 AND err MATCHES "warning: the reference's own noise is .*--reference-samples")
expect_failure("compare: a variance and a second reference" "give one" "" "${VPLKIT}" compare "${WORK}/r3.pfm" "${WORK}/r1.pfm" --second-reference "${WORK}/r2.pfm"
               --reference-variance "${WORK}/r2.pfm")

cli_report()
