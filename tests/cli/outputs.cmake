# Outputs that are not regular files, and standard output: a device node or a FIFO named as an
# output is written through (as cp does) and stays what it is; /dev/full's ENOSPC is an error with
# the system's reason; a link to a file replaces the file and stays a link, a dangling one is
# refused; `-o -` and `-o /dev/stdout` print the text; a failed write to standard output exits 1.
# Device nodes are made with mknod in this part's scratch folder, never the real /dev (the old bug
# replaced the node with a regular file); where mknod is not permitted those checks are skipped,
# saying so.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# expect_node(<name> <path> <test flag: -c, -p, -h> [<major,minor hex as stat %t,%T>]): the entry is
# still that kind of node (and that device).
function(expect_node name path flag)
  execute_process(COMMAND test ${flag} "${path}" RESULT_VARIABLE code)
  set(numbers "")
  if(ARGC GREATER 3)
    execute_process(COMMAND stat -c "%t,%T" "${path}" OUTPUT_VARIABLE numbers OUTPUT_STRIP_TRAILING_WHITESPACE)
  endif()
  if(NOT code EQUAL 0 OR (ARGC GREATER 3 AND NOT numbers STREQUAL "${ARGV3}"))
    execute_process(COMMAND ls -l "${path}" OUTPUT_VARIABLE listing ERROR_VARIABLE listing)
    message(SEND_ERROR "FAILED ${name}: ${path} is no longer what it was (test ${flag}: ${code}, device ${numbers}): ${listing}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}")
  endif()
endfunction()

# expect_lost_stdout(<name> <args...>): the command's standard output is the full device: exit 1
# and the system's reason (it once exited 0 with its results lost).
function(expect_lost_stdout name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_FILE "${WORK}/full" ERROR_VARIABLE err)
  if(NOT code EQUAL 1 OR NOT err MATCHES "vplkit: error: cannot write to standard output: No space left on device")
    message(SEND_ERROR "FAILED ${name}: exit ${code}, stderr: ${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}: ${err}")
  endif()
endfunction()

set(F "${WORK}/main.frag")
file(WRITE "${F}" "#version 330 core\n#include \"lib/irradiance.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(1.0); }\n")
set(expand "${VPLKIT}" shader expand "${F}" --shader-dir "${SHADERS}")
execute_process(COMMAND ${expand} RESULT_VARIABLE code OUTPUT_VARIABLE expanded)
expect_true("the expansion to standard output" code EQUAL 0 AND expanded MATCHES "^#version 330 core\n.*vec3 pixel_light_irradiance")

# -o - and -o /dev/stdout: the text itself on standard output, no "wrote" line, no file named "-".
foreach(out - /dev/stdout)
  execute_process(COMMAND ${expand} -o "${out}" WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE code OUTPUT_VARIABLE text)
  expect_true("-o ${out} prints the expansion and nothing else" code EQUAL 0 AND text STREQUAL expanded)
endforeach()
expect_true("-o - made no file named -" NOT EXISTS "${WORK}/-")
expect_failure("--depfile with -o -" "--depfile names the dependencies of -o OUT; give -o with a file" "${WORK}/x.d" ${expand} -o - --depfile "${WORK}/x.d")

# A FIFO: its reader gets the bytes (vplkit waits for it, as cp does), and it stays a FIFO. The
# reader drains vplkit's own standard output after the FIFO, so that the "wrote" line has a reader.
execute_process(COMMAND mkfifo "${WORK}/expanded.glsl" "${WORK}/frame.png" RESULT_VARIABLE code)
expect_true("mkfifo" code EQUAL 0)
execute_process(COMMAND ${expand} -o "${WORK}/expanded.glsl"
                COMMAND sh -c "cat \"$0\"; cat > \"$1\"" "${WORK}/expanded.glsl" "${WORK}/drained.txt"
                RESULTS_VARIABLE codes OUTPUT_VARIABLE received TIMEOUT 120)
string(REPLACE ";" "," codes "${codes}")  # both exit codes, e.g. "0,0"
expect_true("shader expand -o FIFO: exit 0 and the reader got the expansion (${codes})" codes STREQUAL "0,0" AND received STREQUAL expanded)
expect_node("the FIFO is still a FIFO" "${WORK}/expanded.glsl" -p)
# render --out FIFO: the PNG goes to the reader, the other images next to it are files.
execute_process(COMMAND "${VPLKIT}" render --size 16 --rsm-size 16 --out "${WORK}/frame.png"
                COMMAND sh -c "cat \"$0\" > \"$1\"; cat > \"$2\"" "${WORK}/frame.png" "${WORK}/received.png" "${WORK}/drained.txt"
                RESULTS_VARIABLE codes TIMEOUT 120)
string(REPLACE ";" "," codes "${codes}")
file(READ "${WORK}/received.png" signature LIMIT 8 HEX)
expect_true("render --out FIFO: exit 0, the reader got a PNG (${codes}, ${signature})" codes STREQUAL "0,0" AND signature STREQUAL "89504e470d0a1a0a")
expect_node("the render's FIFO is still a FIFO" "${WORK}/frame.png" -p)
expect_true("the render's other outputs are files next to it" EXISTS "${WORK}/frame-indirect.pfm")

# Links: to a regular file, the file gets the text and the link stays; a dangling link is refused
# and nothing appears where it points.
file(MAKE_DIRECTORY "${WORK}/real")
file(WRITE "${WORK}/real/target.glsl" "old\n")
file(CREATE_LINK "${WORK}/real/target.glsl" "${WORK}/link.glsl" SYMBOLIC)
expect_success("-o a link to a file" "wrote" ${expand} -o "${WORK}/link.glsl")
file(READ "${WORK}/real/target.glsl" through_link)
expect_true("the link's file holds the expansion" through_link STREQUAL expanded)
expect_node("the link is still a link" "${WORK}/link.glsl" -h)
file(CREATE_LINK "${WORK}/nowhere/x.glsl" "${WORK}/dangling.glsl" SYMBOLIC)
expect_failure("-o a dangling link" "cannot write ${WORK}/dangling\\.glsl: it is a link to ${WORK}/nowhere/x\\.glsl, which does not exist" "${WORK}/nowhere"
               ${expand} -o "${WORK}/dangling.glsl")
expect_node("the dangling link is still a link" "${WORK}/dangling.glsl" -h)

# Device nodes, made here: the null device (1,3) takes the bytes, the full one (1,7) refuses them
# with ENOSPC; both stay the devices they were, and so does a link to one.
execute_process(COMMAND mknod "${WORK}/null" c 1 3 RESULT_VARIABLE null_code ERROR_VARIABLE why)
execute_process(COMMAND mknod "${WORK}/full" c 1 7 RESULT_VARIABLE full_code ERROR_VARIABLE why_full)
if(NOT null_code EQUAL 0 OR NOT full_code EQUAL 0)
  message(STATUS "skipped the device-node checks: mknod is not permitted here (${why}${why_full})")
else()
  expect_success("-o a null device node" "wrote ${WORK}/null" ${expand} -o "${WORK}/null")
  expect_node("the null node is still the null device" "${WORK}/null" -c "1,3")
  expect_failure("-o a full device node" "cannot write ${WORK}/full \\(a character device, written through\\): No space left on device" ""
                 ${expand} -o "${WORK}/full")
  expect_node("the full node is still the full device" "${WORK}/full" -c "1,7")
  file(CREATE_LINK "${WORK}/full" "${WORK}/to-full.png" SYMBOLIC)
  expect_failure("render --out a link to the full device" "to-full\\.png \\(a character device, written through\\): No space left on device" ""
                 "${VPLKIT}" render --size 16 --rsm-size 16 --out "${WORK}/to-full.png")
  expect_node("the link to it is still a link" "${WORK}/to-full.png" -h)
  expect_node("and the node the full device" "${WORK}/full" -c "1,7")
  expect_true("a failed set installs none of its files" NOT EXISTS "${WORK}/to-full-indirect.pfm")
  # Standard output on the full device: every command that prints results exits 1 and says why.
  expect_lost_stdout("shader expand > full" ${expand})
  expect_lost_stdout("shader expand -o - > full" ${expand} -o -)
  expect_lost_stdout("info > full" "${VPLKIT}" info)
  expect_lost_stdout("--help > full" "${VPLKIT}" --help)
  expect_lost_stdout("render > full (its pass tables and wrote lines)" "${VPLKIT}" render --size 16 --rsm-size 16 --out "${WORK}/lost.png")
  expect_success("reference for compare" "wrote" "${VPLKIT}" reference --size 16 --samples 1 --out "${WORK}/ref.pfm")
  expect_lost_stdout("compare > full" "${VPLKIT}" compare "${WORK}/ref.pfm" "${WORK}/ref.pfm")
  expect_node("the full node is still the full device after the redirections" "${WORK}/full" -c "1,7")
endif()

cli_report()
