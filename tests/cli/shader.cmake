# vplkit shader expand: one's own GLSL with its includes expanded from one's own folders and
# vplkit's shaders, written whole; the usage errors (exit 2) and the failures (exit 1).
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# expect_match(<name> <variable> <regex>): the variable's text matches (a function, so that the
# regex is not parsed again as expect_true's arguments are).
function(expect_match name variable pattern)
  if("${${variable}}" MATCHES "${pattern}")
    message(STATUS "ok ${name}")
  else()
    message(SEND_ERROR "FAILED ${name}: the text does not match '${pattern}':\n${${variable}}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  endif()
endfunction()

set(R "${WORK}/mine")
file(WRITE "${R}/my/two_lights.glsl" "// mine\n#include \"lib/irradiance.glsl\"\n#include \"my/helper.glsl\"\nvec3 two(vec3 a) { return helper(a); }\n")
file(WRITE "${R}/my/helper.glsl" "#include \"lib/irradiance.glsl\"\nvec3 helper(vec3 a) { return a; }\n")
file(WRITE "${WORK}/main.frag" "#version 330 core\n#include \"my/two_lights.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(two(vec3(VALUE)), 1.0); }\n")

# To standard output: vplkit's twin once (included twice), the folder's files, #line directives
# back to every file and the table of their numbers.
execute_process(COMMAND "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "vec3 pixel_light_irradiance\\(" definitions "${out}")
list(LENGTH definitions definition_count)
string(FIND "${out}" "#include" include_left)
expect_true("expand: exit 0" code EQUAL 0)
expect_match("expand: #version first" out "^#version 330 core\n")
expect_true("expand: the twin is in once, though included twice" definition_count EQUAL 1)
expect_true("expand: no #include is left" include_left EQUAL -1)
expect_match("expand: the folder's files, then the top file's lines at their own numbers" out
             "vec3 helper\\(vec3 a\\).*vec3 two\\(vec3 a\\).*#line 3 0\nout vec4 colour;")
expect_match("expand: the table of the #line numbers" out
             "// vplkit shader expand: the source-string numbers of the #line directives: 0 [^\n]*main\\.frag, 1 my/two_lights\\.glsl, 2 lib/irradiance\\.glsl, 3 my/helper\\.glsl\n$")

# Into a file, with a #define after #version and a depfile naming every file read.
expect_success("expand -o with --define and --depfile" "wrote ${WORK}/out/main\\.frag\nwrote ${WORK}/out/main\\.frag\\.d"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}" -D VALUE=0.5
               -o "${WORK}/out/main.frag" --depfile "${WORK}/out/main.frag.d")
file(READ "${WORK}/out/main.frag" written)
file(READ "${WORK}/out/main.frag.d" depfile)
expect_match("the file has the define right after #version" written "^#version 330 core\n#define VALUE 0\\.5\n")
# Make's syntax escapes a space in a path as "\ ": the paths as the depfile writes them (a
# checkout's path may hold spaces), as regular expressions.
foreach(folder WORK R SHADERS)
  string(REPLACE " " "\\\\ " ${folder}_in_depfile "${${folder}}")
endforeach()
expect_match("the depfile names the output and each file read" depfile
             "^${WORK_in_depfile}/out/main\\.frag: ${WORK_in_depfile}/main\\.frag ${R_in_depfile}/my/two_lights\\.glsl ${SHADERS_in_depfile}/lib/irradiance\\.glsl ${R_in_depfile}/my/helper\\.glsl\n$")

# A folder given with --root is searched before vplkit's shaders: its own lib/irradiance.glsl wins.
file(WRITE "${WORK}/shadow/lib/irradiance.glsl" "float my_own_irradiance() { return 1.0; }\n")
expect_success("--root shadows a vplkit file of the same name" "float my_own_irradiance\\(\\)"
               "${VPLKIT}" shader expand "${R}/my/helper.glsl" --root "${WORK}/shadow" --shader-dir "${SHADERS}")
# Without --root, includes are vplkit's own: a lib file expands on its own.
expect_success("a vplkit lib file expands with no --root" "vec3 pixel_light_irradiance.*struct rsm_texel.*vec3 gather_rsm"
               "${VPLKIT}" shader expand "${SHADERS}/lib/rsm_gather.glsl" --shader-dir "${SHADERS}")

# Usage errors: exit 2, no file.
expect_failure("shader without a subcommand" "A subcommand is required" "" "${VPLKIT}" shader)
expect_failure("expand without a file" "file is required" "" "${VPLKIT}" shader expand)
expect_failure("--root that is not a folder" "--root.*Directory does not exist: ${WORK}/nowhere" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${WORK}/nowhere" -o "${WORK}/x.frag")
expect_failure("--define that is not NAME=VALUE" "--define '1X=2': expected NAME=VALUE" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}" -D 1X=2 -o "${WORK}/x.frag")
expect_failure("-o naming the input" "-o ${WORK}/main\\.frag is the input" ""
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}" -o "${WORK}/main.frag")
expect_failure("--depfile without -o" "--depfile names the dependencies of -o OUT" "${WORK}/x.d"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}" --depfile "${WORK}/x.d")

# Failures: exit 1, a message naming the file and line, no file written.
expect_failure("a missing file" "shader file not found: ${WORK}/absent\\.frag" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/absent.frag" --shader-dir "${SHADERS}" -o "${WORK}/x.frag")
expect_failure("an include found in no folder names the line and every folder"
               "main\\.frag:2: included file \"my/two_lights\\.glsl\" not found \\(looked in ${SHADERS}\\)" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --shader-dir "${SHADERS}" -o "${WORK}/x.frag")
expect_failure("--define into a file without #version" "two_lights\\.glsl has no #version line first" "${WORK}/x.glsl"
               "${VPLKIT}" shader expand "${R}/my/two_lights.glsl" --root "${R}" --shader-dir "${SHADERS}" -D A=1 -o "${WORK}/x.glsl")
file(WRITE "${WORK}/a-file" "")
expect_failure("an output that cannot be written" "cannot write ${WORK}/a-file/x\\.frag" "${WORK}/a-file/x.frag"
               "${VPLKIT}" shader expand "${WORK}/main.frag" --root "${R}" --shader-dir "${SHADERS}" -o "${WORK}/a-file/x.frag")

# Lines it does not expand are refused, naming the file and line (they were left in the
# "self-contained" output, to fail later as a driver's compile error): each spelling of #include
# other than `#include "path"` with at most a // comment after it.
set(refused_lines "#include <lib/irradiance.glsl>" "#include \"lib/irradiance.glsl\" junk" "#include \"lib/irradiance.glsl" "#include \"\"")
set(refused_reasons "#include <\\.\\.\\.> is not expanded" "text after the file name: 'junk'" "the file name has no closing quote" "the file name is empty")
foreach(i RANGE 3)
  list(GET refused_lines ${i} line)
  list(GET refused_reasons ${i} reason)
  file(WRITE "${WORK}/refused${i}.frag" "#version 330 core\n// line 2\n${line}\nvoid main() {}\n")
  expect_failure("an #include line it does not expand: ${line}" "refused${i}\\.frag:3: ${reason}" "${WORK}/x.frag"
                 "${VPLKIT}" shader expand "${WORK}/refused${i}.frag" --shader-dir "${SHADERS}" -o "${WORK}/x.frag")
endforeach()
file(WRITE "${R}/my/bad.glsl" "float bad();\n#include <lib/irradiance.glsl>\n")
file(WRITE "${WORK}/nested.frag" "#version 330 core\n#include \"my/bad.glsl\"\n")
expect_failure("an unexpanded #include in an included file names that file" "my/bad\\.glsl:2: #include <" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/nested.frag" --root "${R}" --shader-dir "${SHADERS}" -o "${WORK}/x.frag")

# CR, LF and CRLF line ends expand alike: a CR-only file's include was one long line, never expanded.
foreach(ending "\r" "\r\n")
  string(REPLACE "\n" "${ending}" text "#version 330 core\n#include \"my/two_lights.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(two(vec3(VALUE)), 1.0); }\n")
  file(WRITE "${WORK}/ends.frag" "${text}")
  execute_process(COMMAND "${VPLKIT}" shader expand "${WORK}/ends.frag" --root "${R}" --shader-dir "${SHADERS}" RESULT_VARIABLE code OUTPUT_VARIABLE ends_out)
  string(FIND "${ends_out}" "#include" include_left)
  string(FIND "${ends_out}" "\r" cr_left)
  string(REGEX MATCHALL "vec3 pixel_light_irradiance\\(" definitions "${ends_out}")
  list(LENGTH definitions definition_count)
  string(HEX "${ending}" ending_hex)
  expect_true("line ends ${ending_hex}: exit 0, every include expanded once, LF line ends out" code EQUAL 0 AND include_left EQUAL -1 AND cr_left EQUAL -1
              AND definition_count EQUAL 1)
  expect_match("line ends ${ending_hex}: the top file's lines keep their numbers" ends_out "vec3 helper\\(vec3 a\\).*#line 3 0\nout vec4 colour;")
endforeach()

# A NUL byte (CMake cannot write one: printf does) is refused with its file, line and offset.
execute_process(COMMAND printf "#version 330 core\\nvoid main() {}\\nfloat x\\000;\\n" OUTPUT_FILE "${WORK}/nul.frag")
expect_failure("a NUL byte" "nul\\.frag:3: a NUL byte \\(byte offset 40 of the file\\)" "${WORK}/x.frag"
               "${VPLKIT}" shader expand "${WORK}/nul.frag" --shader-dir "${SHADERS}" -o "${WORK}/x.frag")

cli_report()
