# `cmake --install` of the build BUILD into PREFIX, emptied first, so that a file the install
# rules stopped installing cannot linger there and hide it from the consumer projects.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${PREFIX}" RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${PREFIX} failed (exit ${code})")
endif()
