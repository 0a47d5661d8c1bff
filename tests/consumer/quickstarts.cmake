# Runs the README's three quick starts as a reader would, from the page itself: the code blocks
# after `<!-- quickstart: FILE -->` (tests/doc_blocks.cmake), built against an installed vplkit.
#   cmake -DDOC=<README.md> -DPREFIX=<install prefix> -DVPLKIT=<vplkit> -DSOURCE=<source tree>
#         -DWORK=<scratch> -DGENERATOR=<generator> [-DCXX=<compiler>] [-DLAUNCHER=<launcher>] -P quickstarts.cmake
# - embed a kernel: the project builds, and its program prints what the page says it prints;
# - test your own shader: the project builds and its test passes; with the GLSL off by 0.1 %
#   (read at run time, no rebuild) the same test fails naming the worst texel;
# - sweep a setting: the page's commands run (the sweep at a small size, --size 32 --rsm-size 64
#   added, so that the brute force takes a second) and write a row per radius.
cmake_minimum_required(VERSION 3.20)
foreach(variable DOC PREFIX VPLKIT SOURCE WORK GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "quickstarts.cmake needs -D${variable}=...")
  endif()
endforeach()
include(${CMAKE_CURRENT_LIST_DIR}/doc_project.cmake)
file(REMOVE_RECURSE "${WORK}")
vplkit_doc_project_files("${DOC}" quickstart "${WORK}" kernel/CMakeLists.txt kernel/main.cpp kernel/expected.txt parity/CMakeLists.txt
                         parity/shaders/my/light.glsl parity/test_my_light.cpp sweep/run.sh)
vplkit_doc_project_finds("${quickstart_text_kernel_CMakeLists_txt}" "the kernel quick start" vplkit)
vplkit_doc_project_finds("${quickstart_text_parity_CMakeLists_txt}" "the parity quick start" vplkit doctest)
# The sweep's commands write output/ relative to their own folder.
set(DOC_PROJECT_WORKING_DIRECTORY "${WORK}/sweep")
file(MAKE_DIRECTORY "${WORK}/sweep/output")

# Embed a kernel: what it prints is what the page says.
vplkit_doc_project_build("${WORK}/kernel" "${WORK}/kernel/build" "the kernel quick start")
vplkit_doc_project_run("running my_renderer" pass "${WORK}/kernel/build/my_renderer")
file(READ "${WORK}/kernel/expected.txt" printed)
if(NOT output STREQUAL printed)
  message(FATAL_ERROR "my_renderer printed '${output}'; the README says it prints '${printed}'")
endif()

# Test your own shader: passes as written; fails with the GLSL off by 0.1 %.
vplkit_doc_project_build("${WORK}/parity" "${WORK}/parity/build" "the parity quick start")
vplkit_doc_project_run("the parity quick start's test" pass "${WORK}/parity/build/my_tests")
file(READ "${WORK}/parity/shaders/my/light.glsl" glsl)
string(REPLACE "irradiance_settings(0.01))" "irradiance_settings(0.01)) * 1.001" off "${glsl}")
if(off STREQUAL glsl)
  message(FATAL_ERROR "the parity quick start's GLSL has no 'irradiance_settings(0.01))' to perturb")
endif()
file(WRITE "${WORK}/parity/shaders/my/light.glsl" "${off}")
vplkit_doc_project_run("the parity quick start's test with the GLSL off by 0.1 %" fail "${WORK}/parity/build/my_tests")
if(NOT "${output}${errors}" MATCHES "parity of my_light failed: [0-9]+ values outside tolerance.*worst texel")
  message(FATAL_ERROR "the failing parity test does not name its worst texel:\n${output}${errors}")
endif()

# Sweep a setting: the page's commands, `build/vplkit` and `scripts/` being this build's and
# this source tree's, run in a folder of their own (output/ relative to it).
string(REPLACE "\\\n" " " commands "${quickstart_text_sweep_run_sh}")
string(REPLACE "\n" ";" commands "${commands}")
set(ran 0)
foreach(line ${commands})
  separate_arguments(words UNIX_COMMAND "${line}")
  if(NOT words)
    continue()
  endif()
  list(GET words 0 program)
  list(REMOVE_AT words 0)
  if(program STREQUAL "build/vplkit")
    vplkit_doc_project_run("vplkit ${words}" pass "${VPLKIT}" ${words} --size 32 --rsm-size 64)
  elseif(program MATCHES "^scripts/")
    vplkit_doc_project_run("${program}" pass "${SOURCE}/${program}" ${words})
  else()
    message(FATAL_ERROR "the sweep quick start runs '${program}', which this test does not know")
  endif()
  math(EXPR ran "${ran} + 1")
endforeach()
file(STRINGS "${WORK}/sweep/output/room-radius/sweep.csv" rows)
list(LENGTH rows row_count)
if(NOT ran EQUAL 2 OR NOT row_count EQUAL 5)
  message(FATAL_ERROR "the sweep quick start ran ${ran} commands and wrote ${row_count} lines of sweep.csv (expected 2, and a header and 4 rows)")
endif()
message(STATUS "ok the sweep quick start wrote a row per radius")
