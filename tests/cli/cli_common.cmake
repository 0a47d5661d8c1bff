# What every part of the command-line test shares (tests/cli/<part>.cmake includes it first).
# Each part is its own ctest entry, so `ctest -j` runs the parts side by side; a part makes every
# file it reads itself, in its own scratch folder.
# Inputs: VPLKIT (the executable), SHADERS (the source shaders/ folder), WORK (the part's scratch
# folder), XVFB_RUN (xvfb-run, or empty), FUZZ_INPUTS (tests/fuzz/regressions: binary inputs
# CMake cannot write), WITH_OSMESA (whether the build has the OSMesa context).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(failures 0)

# expect_failure(<name> <message regex> <files that must not exist: a path or a glob, or ""> <args...>):
# exit code 1 or 2, the message, and no file matching the glob (any found are removed after).
function(expect_failure name pattern must_not_exist)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(left "")
  if(NOT must_not_exist STREQUAL "")
    file(GLOB left "${must_not_exist}")
  endif()
  set(problem "")
  if(NOT (code EQUAL 1 OR code EQUAL 2))
    set(problem "exit code ${code}, expected 1 or 2")
  elseif(NOT "${out}${err}" MATCHES "${pattern}")
    set(problem "output does not match '${pattern}'")
  elseif(left)
    set(problem "left files behind: ${left}")
  endif()
  if(left)
    file(REMOVE_RECURSE ${left})
  endif()
  if(problem)
    message(SEND_ERROR "FAILED ${name}: ${problem}\n  command: ${ARGN}\n  exit: ${code}\n  stdout: ${out}\n  stderr: ${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}: exit ${code}, message: ${err}")
  endif()
endfunction()

# expect_success(<name> <stdout regex> <args...>): exit code 0 and the output.
function(expect_success name pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR NOT "${out}" MATCHES "${pattern}")
    message(SEND_ERROR "FAILED ${name}: exit ${code}\n  command: ${ARGN}\n  stdout: ${out}\n  stderr: ${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}")
  endif()
endfunction()

# expect_true(<name> <condition...>): a check of files or values the part computed itself.
# A macro re-parses its arguments: a regular expression in the condition writes [.] and [(], not
# "\\." or "\\(", whose backslash that second parse reads as a bad escape (CMP0010).
macro(expect_true name)
  if(${ARGN})
    message(STATUS "ok ${name}")
  else()
    message(SEND_ERROR "FAILED ${name}")
    math(EXPR failures "${failures} + 1")
  endif()
endmacro()

# compare_within(<name> <image> <reference> <max RMSE>): `vplkit compare` and its RMSE at most the bound.
function(compare_within name candidate reference bound)
  execute_process(COMMAND "${VPLKIT}" compare "${candidate}" "${reference}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCH "\\| RMSE \\| ([0-9.e+-]+) \\|" found "${out}")
  if(NOT code EQUAL 0 OR NOT found OR NOT CMAKE_MATCH_1 LESS_EQUAL bound)
    message(SEND_ERROR "FAILED ${name}: RMSE '${CMAKE_MATCH_1}' (bound ${bound}), exit ${code}\n  ${out}${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}: RMSE ${CMAKE_MATCH_1} <= ${bound}")
  endif()
endfunction()

# The last line of every part.
macro(cli_report)
  if(failures GREATER 0)
    message(FATAL_ERROR "${failures} CLI check(s) failed")
  endif()
endmacro()
