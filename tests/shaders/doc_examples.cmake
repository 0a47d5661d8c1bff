# Compiles every GLSL example of a docs page as a reader would: the code block as the page shows
# it, its includes expanded by `vplkit shader expand` with vplkit's shaders, then glslang.
#   cmake -DDOC=<the .md> -DVPLKIT=<vplkit> -DSHADERS=<shaders folder> -DGLSLANG=<glslangValidator>
#         -DWORK=<scratch folder> -P doc_examples.cmake
#
# Every fenced ```glsl block of the page must follow a line `<!-- example: NAME.frag -->` (or
# .vert, .comp: the stage glslang compiles it as), so that a new example cannot slip past the
# test unmarked; marked blocks of other languages are left to the tests that build them. An
# example begins with its own #version line (the page's examples are GLSL 3.30 core or later)
# and is compiled as that version. One that stops before main() (its prose says what main does)
# gets an empty one appended: what such an example shows is its declarations and the includes
# they need, which glslang checks all the same (it compiles every function, called or not).
cmake_minimum_required(VERSION 3.20)
foreach(variable DOC VPLKIT SHADERS GLSLANG WORK)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "doc_examples.cmake needs -D${variable}=...")
  endif()
endforeach()
if(NOT GLSLANG)
  message(FATAL_ERROR "glslangValidator was not found when CMake ran: install glslang-tools (scripts/setup.sh does) and reconfigure")
endif()

file(READ "${DOC}" page)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/expanded")
set(rest "\n${page}")
set(consumed 0)  # characters of "\n${page}" before `rest`, for line numbers
set(names "")
set(fence "\n```glsl\n")
string(LENGTH "${fence}" fence_length)
while(TRUE)
  string(FIND "${rest}" "${fence}" at)
  if(at EQUAL -1)
    break()
  endif()
  string(SUBSTRING "${rest}" 0 ${at} before)
  # The page's line of the fence: the newlines before it, the leading one added above excluded.
  string(SUBSTRING "\n${page}" 0 ${consumed} done)
  string(REGEX MATCHALL "\n" newlines "${done}${before}\n")
  list(LENGTH newlines line)
  # The marker is the line right before the fence.
  string(FIND "${before}" "\n" last_newline REVERSE)
  math(EXPR marker_start "${last_newline} + 1")
  string(SUBSTRING "${before}" ${marker_start} -1 marker)
  if(NOT marker MATCHES "^<!-- example: ([A-Za-z0-9_.-]+\\.(frag|vert|comp)) -->$")
    message(FATAL_ERROR "${DOC}:${line}: a ```glsl block without a line '<!-- example: NAME.frag -->' (or .vert, .comp) "
                        "right before it; every GLSL example of the page is compiled by this test (found '${marker}')")
  endif()
  set(name "${CMAKE_MATCH_1}")
  if(name IN_LIST names)
    message(FATAL_ERROR "${DOC}:${line}: a second example named ${name}")
  endif()
  list(APPEND names "${name}")
  math(EXPR code_start "${at} + ${fence_length}")
  string(SUBSTRING "${rest}" ${code_start} -1 rest)
  math(EXPR consumed "${consumed} + ${code_start}")
  string(FIND "${rest}" "\n```" code_end)
  if(code_end EQUAL -1)
    message(FATAL_ERROR "${DOC}:${line}: the code block of example ${name} is not closed")
  endif()
  math(EXPR code_length "${code_end} + 1")
  string(SUBSTRING "${rest}" 0 ${code_length} code)
  string(SUBSTRING "${rest}" ${code_length} -1 rest)
  math(EXPR consumed "${consumed} + ${code_length}")
  if(NOT code MATCHES "^#version [0-9]+")
    message(FATAL_ERROR "${DOC}:${line}: example ${name} does not begin with its #version line")
  endif()
  if(NOT code MATCHES "void main\\(")
    string(APPEND code "void main() {}\n")
  endif()
  file(WRITE "${WORK}/${name}" "${code}")
  execute_process(COMMAND "${VPLKIT}" shader expand "${WORK}/${name}" --shader-dir "${SHADERS}" -o "${WORK}/expanded/${name}"
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${DOC}:${line}: vplkit shader expand ${name} failed (exit ${status}):\n${out}${err}")
  endif()
  execute_process(COMMAND "${GLSLANG}" "${WORK}/expanded/${name}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    # The last line of the expanded source maps the #line directives' source-string numbers
    # (glslang's "ERROR: N:LINE:") to file names.
    file(STRINGS "${WORK}/expanded/${name}" table REGEX "^// vplkit shader expand: ")
    message(FATAL_ERROR "${DOC}:${line}: example ${name} does not compile (glslangValidator, exit ${status}):\n${out}${err}\n${table}")
  endif()
  message(STATUS "ok ${name} (${DOC}:${line})")
endwhile()
list(LENGTH names count)
if(count EQUAL 0)
  message(FATAL_ERROR "${DOC}: no ```glsl example: this test expects the page's examples")
endif()
message(STATUS "${count} GLSL example(s) of ${DOC} compiled: ${names}")
