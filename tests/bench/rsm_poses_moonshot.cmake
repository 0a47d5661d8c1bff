# The pose study's moonshot (issue 39; bench/rsm_poses.cpp, voxel mode): the filtered image's
# per-pixel error against the Monte Carlo image with that image's own noise taken out, its noise
# estimated from a second Monte Carlo image of another seed. The second image must be another seed's
# (the same image twice would estimate no noise and report the raw error as the corrected one), it
# must be cached under its own name beside seed 1's (one file for both would hand one seed's image to
# the other), and a second run must read both back and report the same numbers. voxel.csv holds the
# frame's row at full precision (the table's 2 digits cannot tell 0.849 from the target's 0.85).
#   cmake -DPOSES_TOOL=<vplkit_rsm_poses> -DWORK=<scratch> -P rsm_poses_moonshot.cmake
include("${CMAKE_CURRENT_LIST_DIR}/../cli/cli_common.cmake")

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/poses.txt" "--scene cornell-box  # cornell-box\n")
set(run_command "${POSES_TOOL}" --voxel --poses "${WORK}/poses.txt" --size 32 --rsm-size 32 --seeds 1 --mc-samples 4 --timing 1
                --cache "${WORK}/cache")

execute_process(COMMAND ${run_command} --out "${WORK}/first" RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
expect_true("the voxel mode runs (exit ${code}: ${err})" code EQUAL 0)
file(GLOB seed_1 "${WORK}/cache/*-mc4-r*.pfm")
set(seed_2 ${seed_1})
list(FILTER seed_1 EXCLUDE REGEX "-seed2[.]pfm$")
list(FILTER seed_2 INCLUDE REGEX "-r[0-9]+-seed2[.]pfm$")
list(LENGTH seed_1 count_1)
list(LENGTH seed_2 count_2)
expect_true("one Monte Carlo image of each seed is cached (seed 1: ${seed_1}; seed 2: ${seed_2})" count_1 EQUAL 1 AND count_2 EQUAL 1)
if(count_1 EQUAL 1 AND count_2 EQUAL 1)
  file(SHA256 "${seed_1}" hash_1)
  file(SHA256 "${seed_2}" hash_2)
  expect_true("the two seeds' Monte Carlo images differ" NOT hash_1 STREQUAL hash_2)
endif()

# The report's moonshot: a row in the targets table, and the Monte Carlo image's noise above 0 %
# (4 rays per pixel are noisy; 0.0 % would mean the second image estimated no noise).
set(report "")
if(EXISTS "${WORK}/first/voxel.md")
  file(READ "${WORK}/first/voxel.md" report)
endif()
expect_true("voxel.md has the moonshot's target row" report MATCHES "[|] moonshot: filtered per-pixel rel[.] RMSE vs Monte Carlo, its noise out, <= 10 %")
# (min / median / max over the frames: one frame here)
string(REGEX MATCH "Monte Carlo image's noise [(][^)]*[)] is ([0-9.]+) / " noise_text "${report}")
set(noise "${CMAKE_MATCH_1}")
expect_true("the Monte Carlo image's noise is above 0 % (found '${noise}')" noise AND noise GREATER 0)

# voxel.csv: the frame's numbers at full precision, one field per column of its header.
set(csv "")
if(EXISTS "${WORK}/first/voxel.csv")
  file(STRINGS "${WORK}/first/voxel.csv" csv)
endif()
list(LENGTH csv csv_lines)
expect_true("voxel.csv holds its header and the frame's row (${csv_lines} lines)" csv_lines EQUAL 2)
if(csv_lines EQUAL 2)
  list(GET csv 0 header)
  list(GET csv 1 row)
  string(REGEX MATCHALL "," header_commas "${header}")
  string(REGEX MATCHALL "," row_commas "${row}")
  list(LENGTH header_commas header_count)
  list(LENGTH row_commas row_count)
  expect_true("the row has the header's fields (${row})" row MATCHES "^\"cornell-box\"," AND row_count EQUAL header_count)
endif()

# A second run reads both images from the cache: the same moonshot, frame row included.
execute_process(COMMAND ${run_command} --out "${WORK}/second" RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
expect_true("a second run (exit ${code}: ${err})" code EQUAL 0)
file(GLOB cached "${WORK}/cache/*-mc4-r*.pfm")
list(LENGTH cached count)
expect_true("the second run adds no Monte Carlo image (found: ${cached})" count EQUAL 2)
set(second_report "")
if(EXISTS "${WORK}/second/voxel.md")
  file(READ "${WORK}/second/voxel.md" second_report)
endif()
string(REGEX MATCH "\\| cornell-box \\|[^\n]*" first_row "${report}")
string(REGEX MATCH "\\| cornell-box \\|[^\n]*" second_row "${second_report}")
# The row's last cell is the moonshot (voxel, radial, the noise); the timing cells before it vary.
string(REGEX MATCH "[^|]*\\|$" first_moonshot "${first_row}")
string(REGEX MATCH "[^|]*\\|$" second_moonshot "${second_row}")
expect_true("the cached images give the same moonshot ('${first_moonshot}', then '${second_moonshot}')"
            first_moonshot AND first_moonshot STREQUAL second_moonshot)

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} check(s) failed")
endif()
