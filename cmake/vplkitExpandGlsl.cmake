# vplkit_expand_glsl: GLSL that includes vplkit's twins, expanded at build time into
# self-contained sources (installed with vplkit; vplkitConfig.cmake includes it).
#
#   vplkit_expand_glsl(TARGET <name> SOURCES <file>...
#                      [ROOTS <folder>...] [DEFINES <NAME=VALUE>...] [OUTPUT_DIRECTORY <folder>])
#
# Adds the custom target <name>, built by default, that writes every source with each
# `#include "..."` expanded to OUTPUT_DIRECTORY/<file name> (default:
# ${CMAKE_CURRENT_BINARY_DIR}/<name>). Includes are looked up in the ROOTS in order, then in
# vplkit's installed shaders, so `#include "lib/irradiance.glsl"` is vplkit's twin. DEFINES become
# #define lines right after #version. An output is written again when its source, any file it
# included, or the vplkit executable changes (a depfile). The outputs are in the target's
# property VPLKIT_EXPANDED_GLSL. It runs `vplkit shader expand` (vplkit::cli): the expander of
# vplkit's own shaders and of vplkit::parity.
function(vplkit_expand_glsl)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;OUTPUT_DIRECTORY" "SOURCES;ROOTS;DEFINES")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "vplkit_expand_glsl: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_TARGET OR NOT arg_SOURCES)
    message(FATAL_ERROR "vplkit_expand_glsl: give TARGET <name> and SOURCES <file>...")
  endif()
  if(TARGET ${arg_TARGET})
    message(FATAL_ERROR "vplkit_expand_glsl: a target named ${arg_TARGET} exists already")
  endif()
  if(NOT TARGET vplkit::cli)
    message(FATAL_ERROR "vplkit_expand_glsl needs the vplkit executable (vplkit::cli), and this vplkit was installed without it "
                        "(built with VPLKIT_BUILD_FRONTEND=OFF)")
  endif()
  get_property(shader_dir GLOBAL PROPERTY vplkit_SHADER_DIR)
  set(output_directory "${arg_OUTPUT_DIRECTORY}")
  if(NOT output_directory)
    set(output_directory "${CMAKE_CURRENT_BINARY_DIR}/${arg_TARGET}")
  endif()
  get_filename_component(output_directory "${output_directory}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  set(options --shader-dir "${shader_dir}")
  foreach(root ${arg_ROOTS})
    get_filename_component(root "${root}" ABSOLUTE)
    if(NOT IS_DIRECTORY "${root}")
      message(FATAL_ERROR "vplkit_expand_glsl(${arg_TARGET}): ROOTS ${root} is not a folder")
    endif()
    list(APPEND options --root "${root}")
  endforeach()
  foreach(define ${arg_DEFINES})
    list(APPEND options --define "${define}")
  endforeach()
  set(outputs "")
  foreach(source ${arg_SOURCES})
    get_filename_component(source "${source}" ABSOLUTE)
    get_filename_component(name "${source}" NAME)
    set(output "${output_directory}/${name}")
    if(output IN_LIST outputs)
      message(FATAL_ERROR "vplkit_expand_glsl(${arg_TARGET}): two sources are named ${name}")
    endif()
    add_custom_command(OUTPUT "${output}"
                       COMMAND vplkit::cli shader expand "${source}" ${options} -o "${output}" --depfile "${output}.d"
                       DEPENDS "${source}" "$<TARGET_FILE:vplkit::cli>"
                       DEPFILE "${output}.d"
                       COMMENT "Expanding the GLSL includes of ${name}"
                       VERBATIM)
    list(APPEND outputs "${output}")
  endforeach()
  add_custom_target(${arg_TARGET} ALL DEPENDS ${outputs})
  set_property(TARGET ${arg_TARGET} PROPERTY VPLKIT_EXPANDED_GLSL ${outputs})
endfunction()
