# What the consumer tests that build a docs page's code (tests/consumer/quickstarts.cmake for the
# README's quick starts, tests/consumer/tutorial/run_tutorial.cmake for the tutorial) share, so
# that a project is written, configured and built the same way a reader does it:
#   vplkit_doc_project_files(<doc> <marker> <destination> <expected file>...)
#       the page's blocks after `<!-- <marker>: FILE -->` (doc_blocks.cmake) written under
#       <destination>; every expected file must come from the page. Sets <marker>_names.
#   vplkit_doc_project_finds(<CMakeLists text> <what> <package>...)
#       the project's find_package calls are exactly these packages: a reader's project finds
#       vplkit (and doctest for a test) and nothing else, so that a dependency vplkit's package
#       forgot fails here as it fails for the reader instead of being found by another package.
#   vplkit_doc_project_run(<description> pass|fail <command>...)
#       runs the command (in DOC_PROJECT_WORKING_DIRECTORY when set); sets output and errors.
#   vplkit_doc_project_build(<source> <build> <what>)
#       configured as the pages say (-DCMAKE_PREFIX_PATH=${PREFIX}), with the suite's generator,
#       compiler (CXX) and launcher (LAUNCHER), then built.
include_guard(GLOBAL)
include(${CMAKE_CURRENT_LIST_DIR}/../doc_blocks.cmake)

function(vplkit_doc_project_files doc marker destination)
  vplkit_doc_blocks("${doc}" ${marker} ${marker})
  foreach(name ${ARGN})
    if(NOT name IN_LIST ${marker}_names)
      message(FATAL_ERROR "${doc} has no code block marked '<!-- ${marker}: ${name} -->' (found: ${${marker}_names})")
    endif()
  endforeach()
  foreach(name ${${marker}_names})
    string(MAKE_C_IDENTIFIER "${name}" key)
    file(WRITE "${destination}/${name}" "${${marker}_text_${key}}")
    set(${marker}_text_${key} "${${marker}_text_${key}}" PARENT_SCOPE)
  endforeach()
  set(${marker}_names "${${marker}_names}" PARENT_SCOPE)
endfunction()

function(vplkit_doc_project_finds text what)
  string(REGEX MATCHALL "find_package\\([A-Za-z0-9_]+" found "${text}")
  string(REPLACE "find_package(" "" found "${found}")
  if(NOT found STREQUAL "${ARGN}")
    string(REPLACE ";" " and " wanted "${ARGN}")
    message(FATAL_ERROR "${what}'s CMakeLists.txt finds '${found}'; a reader's project finds ${wanted}, nothing else")
  endif()
endfunction()

function(vplkit_doc_project_run description expected_result)
  set(directory "")
  if(DOC_PROJECT_WORKING_DIRECTORY)
    set(directory WORKING_DIRECTORY "${DOC_PROJECT_WORKING_DIRECTORY}")
  endif()
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err ${directory})
  if((expected_result STREQUAL "pass" AND NOT code EQUAL 0) OR (expected_result STREQUAL "fail" AND code EQUAL 0))
    message(FATAL_ERROR "${description}: exit ${code}, expected to ${expected_result}:\n${out}${err}")
  endif()
  message(STATUS "ok ${description}")
  set(output "${out}" PARENT_SCOPE)
  set(errors "${err}" PARENT_SCOPE)
endfunction()

function(vplkit_doc_project_build source build what)
  set(configure "${CMAKE_COMMAND}" -S "${source}" -B "${build}" -G "${GENERATOR}" "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_BUILD_TYPE=Release)
  if(CXX)
    list(APPEND configure "-DCMAKE_CXX_COMPILER=${CXX}")
  endif()
  if(LAUNCHER)
    list(APPEND configure "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  endif()
  vplkit_doc_project_run("configuring ${what}" pass ${configure})
  vplkit_doc_project_run("building ${what}" pass "${CMAKE_COMMAND}" --build "${build}")
endfunction()
