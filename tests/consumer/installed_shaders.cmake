# Which shaders an installed vplkit reads (issue 40): its installed ones, even while the source
# tree it was built from exists, unless VPLKIT_SHADER_DIR or --shader-dir says otherwise; the
# build tree's vplkit reads the source tree's. `vplkit shader expand --depfile` names every file
# it read, so each case shows the exact file; a render shows the pass programs follow the same
# rule.
#   cmake -DPREFIX=<an install of this build> -DVPLKIT=<the build tree's vplkit> -DSHADERS=<the
#         source tree's shaders/> -DWORK=<scratch folder> -P installed_shaders.cmake
include("${CMAKE_CURRENT_LIST_DIR}/../cli/cli_common.cmake")

# A copy of the prefix at a path with a space and a non-ASCII letter: the installed shaders are
# found beside the executable, not at the path the build was configured to install to.
set(moved "${WORK}/moved prefix é")
file(COPY "${PREFIX}/" DESTINATION "${moved}")
set(installed "${moved}/bin/vplkit")
set(installed_shaders "${moved}/share/vplkit/shaders")
expect_true("the copied prefix has bin/vplkit and share/vplkit/shaders/lib"
            EXISTS "${installed}" AND IS_DIRECTORY "${installed_shaders}/lib")

file(WRITE "${WORK}/mine/main.frag" "#version 330 core\n#include \"lib/irradiance.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(1.0); }\n")

# expect_reads(<label> <folder> <other folder> <command...>): expanding main.frag with the command
# (and ${extra_options} after the subcommand's) reads <folder>/lib/irradiance.glsl and not <other folder>'s (the depfile names every file read).
function(expect_reads label folder other)
  set(depfile "${WORK}/${label}.d")
  execute_process(COMMAND ${ARGN} shader expand "${WORK}/mine/main.frag" --root "${WORK}/mine" -o "${WORK}/${label}.frag" --depfile "${depfile}" ${extra_options}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(dependencies "")
  if(EXISTS "${depfile}")
    file(READ "${depfile}" dependencies)
    string(REPLACE "\\ " " " dependencies "${dependencies}")  # Make's escape of a space undone
  endif()
  string(FIND "${dependencies}" "${folder}/lib/irradiance.glsl" at)
  string(FIND "${dependencies}" "${other}/lib/irradiance.glsl" other_at)
  if(code EQUAL 0 AND NOT at EQUAL -1 AND other_at EQUAL -1)
    message(STATUS "ok ${label} reads ${folder}/lib/irradiance.glsl")
  else()
    message(SEND_ERROR "FAILED ${label}: expected to read ${folder}/lib/irradiance.glsl, not ${other}'s; exit ${code}, "
                       "files read: ${dependencies}${out}${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  endif()
endfunction()

set(no_override ${CMAKE_COMMAND} -E env --unset=VPLKIT_SHADER_DIR)
expect_reads("installed vplkit, no override" "${installed_shaders}" "${SHADERS}" ${no_override} "${installed}")
expect_reads("installed vplkit, VPLKIT_SHADER_DIR=source" "${SHADERS}" "${installed_shaders}"
             ${CMAKE_COMMAND} -E env "VPLKIT_SHADER_DIR=${SHADERS}" "${installed}")
set(extra_options --shader-dir "${SHADERS}")
expect_reads("installed vplkit, --shader-dir source" "${SHADERS}" "${installed_shaders}" ${no_override} "${installed}")
set(extra_options "")
expect_reads("build tree's vplkit, no override" "${SHADERS}" "${installed_shaders}" ${no_override} "${VPLKIT}")

# The pass programs: a copy of the installed shaders that does not compile breaks the installed
# vplkit's render, naming the installed file, and leaves one pointed at the source tree intact.
file(READ "${installed_shaders}/lib/irradiance.glsl" original)
file(WRITE "${installed_shaders}/lib/irradiance.glsl" "#error the installed copy was read\n${original}")
expect_failure("installed vplkit renders with its installed (broken) shaders" "the installed copy was read" "${WORK}/installed.png"
               ${no_override} "${installed}" render --size 8 --rsm-size 16 --out "${WORK}/installed.png")
expect_success("installed vplkit with VPLKIT_SHADER_DIR=<source tree> renders" "technique rsm-alg6"
               ${CMAKE_COMMAND} -E env "VPLKIT_SHADER_DIR=${SHADERS}" "${installed}" render --size 8 --rsm-size 16 --out "${WORK}/source.png")
expect_success("the build tree's vplkit renders from the source tree" "technique rsm-alg6"
               ${no_override} "${VPLKIT}" render --size 8 --rsm-size 16 --out "${WORK}/build-tree.png")

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} check(s) failed")
endif()
