# Runs docs/testing-your-shaders.md as a reader would: takes the tutorial's files from the page
# itself, builds them against an installed vplkit, and checks both outcomes the page shows.
#   cmake -DDOC=<the .md> -DPREFIX=<install prefix> -DWORK=<scratch folder> -DGENERATOR=<generator>
#         [-DCXX=<compiler>] [-DLAUNCHER=<compiler launcher>] -P run_tutorial.cmake
#
# A file of the tutorial is every fenced code block that follows a line `<!-- tutorial: FILE -->`,
# the blocks of one FILE joined in the page's order. The project is the page's CMakeLists.txt,
# verbatim: it may find vplkit and doctest and nothing else, so that a dependency vplkit's
# package forgot (Threads::Threads, once) fails here as it fails for a reader, instead of being
# found by another package's config. The test as written must fail with a report naming the
# worst texel (step 4: the GLSL has a `* 1.001`), and pass once `* 1.001` is removed (step 5).
cmake_minimum_required(VERSION 3.20)
foreach(variable DOC PREFIX WORK GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_tutorial.cmake needs -D${variable}=...")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../doc_project.cmake)
set(source "${WORK}/two_lights")
set(build "${WORK}/build")
file(REMOVE_RECURSE "${WORK}")
# The files the page's project layout names: each must come from the page.
vplkit_doc_project_files("${DOC}" tutorial "${source}" CMakeLists.txt shaders/my/two_lights.glsl two_lights.hpp test_two_lights.cpp)
message(STATUS "the tutorial's files, from ${DOC}: ${tutorial_names}")
vplkit_doc_project_finds("${tutorial_text_CMakeLists_txt}" "the tutorial" vplkit doctest)
vplkit_doc_project_build("${source}" "${build}" "the tutorial's project")

# Step 4: the bug in the GLSL is reported, with its worst texel.
vplkit_doc_project_run("step 4, ctest with '* 1.001' in the GLSL" fail "${CMAKE_CTEST_COMMAND}" --test-dir "${build}" --output-on-failure)
foreach(expected "ERROR: parity of two_lights_irradiance failed: [0-9]+ values outside tolerance, 0 allowed"
                 "worst texel \\([0-9]+, [0-9]+\\)\\.[xyz]: gpu=[^ ]+ cpu=[^ ]+ \\(abs [^ ]+ of [^ ]+ allowed" " fin5=\\("
                 "tolerance: abs <= 6e-06 x the texel's abs_scale")
  if(NOT "${output}${errors}" MATCHES "${expected}")
    message(FATAL_ERROR "step 4's report has no '${expected}':\n${output}${errors}")
  endif()
endforeach()

# Step 5: "Remove `* 1.001` and run again".
file(READ "${source}/shaders/my/two_lights.glsl" glsl)
string(REPLACE " * 1.001" "" fixed "${glsl}")
if(fixed STREQUAL glsl)
  message(FATAL_ERROR "the tutorial's two_lights.glsl has no ' * 1.001' for step 5 to remove")
endif()
file(WRITE "${source}/shaders/my/two_lights.glsl" "${fixed}")
vplkit_doc_project_run("step 5, ctest without '* 1.001'" pass "${CMAKE_CTEST_COMMAND}" --test-dir "${build}" -V)
if(NOT "${output}${errors}" MATCHES "MESSAGE: parity two_lights_irradiance: 30000 values, 0 outside tolerance \\(allowed 0\\)")
  message(FATAL_ERROR "step 5's summary line is missing:\n${output}${errors}")
endif()
message(STATUS "the tutorial fails at step 4 and passes at step 5, as the page says")
