# vplkit shader block NAME: the std140 uniform block of a settings struct's GLSL twin, with its
# size and every offset (vplkit/std140.hpp; tests/frontend/gl/test_std140_gl.cpp compiles the same
# text and checks the offsets against GL's); the usage errors (exit 2).
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

expect_success("block: the nested struct, its size, the array's stride, the names given"
               "^// rsm_gather_settings in std140: 384 bytes [^\n]*\n//   offset 0: float gather\\.irradiance\\.min_distance\n.*//   offset 52: uint gather\\.radial\\.seed\n.*//   offset 112: float gather\\.slots\\.boundary_tangent\\[15\\], stride 16\n.*//   offset 368: int gather\\.perspective\nlayout\\(std140\\) uniform gather_block {\n  rsm_gather_settings gather;\n};\n$"
               "${VPLKIT}" shader block rsm_gather_settings --block gather_block --member gather)
expect_success("block: the default block and member names"
               "layout\\(std140\\) uniform irradiance_settings_block {\n  irradiance_settings settings;\n};\n$"
               "${VPLKIT}" shader block irradiance_settings)
expect_success("block: a vec3 followed by a float shares its 16 bytes" "//   offset 32: vec3 settings\\.intensity\n//   offset 44: float settings\\.cos_inner\n"
               "${VPLKIT}" shader block spot_light)

expect_failure("block: an unknown struct lists the known ones"
               "no settings struct .no_such_settings. has a GLSL twin \\(known: irradiance_settings, radial_pattern_constants, .*, temporal_settings(, [a-z0-9_]+)*\\)" ""
               "${VPLKIT}" shader block no_such_settings)
# Described, but the GLSL side reads radial_pattern_constants: no block of its own.
expect_failure("block: a settings struct without a GLSL twin" "no settings struct .radial_pattern_settings. has a GLSL twin" ""
               "${VPLKIT}" shader block radial_pattern_settings)
expect_failure("block: a member that is not an identifier" "--member .my member. is not a GLSL identifier" ""
               "${VPLKIT}" shader block spot_light --member "my member")
expect_failure("block: a block name that is not an identifier" "--block .1block. is not a GLSL identifier" ""
               "${VPLKIT}" shader block spot_light --block 1block)
expect_failure("block: a member named as the struct" "--member .spot_light. is the struct's own name" ""
               "${VPLKIT}" shader block spot_light --member spot_light)
expect_failure("block: no NAME" "name is required" "" "${VPLKIT}" shader block)

# Second and third layout implementations: glslang's reflection of every struct's block, compiled
# with the lib files that declare the twins, for OpenGL (GLSL 3.30) and for Vulkan (GLSL 4.50 to
# SPIR-V, --auto-map-bindings, spirv-val'd), against the offsets, strides and size that
# `shader block` prints.
if(GLSLANG STREQUAL "")
  message(STATUS "skipped glslang's std140 reflection: glslangValidator is not installed (Debian glslang-tools)")
else()
  execute_process(COMMAND "${VPLKIT}" shader block no_such_settings RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT err MATCHES "known: ([a-z_, ]+)\\)")
    message(FATAL_ERROR "no list of the known structs in: ${err}")
  endif()
  string(REPLACE ", " ";" twins "${CMAKE_MATCH_1}")
  set(prelude "#define VPLKIT_RSM_PATTERN 0\n#define VPLKIT_VISIBILITY 6\n")
  foreach(lib rsm_gather rsm_packing shadow bilateral direct_light lightwave temporal_accumulation voxel_visibility)
    string(APPEND prelude "#include \"lib/${lib}.glsl\"\n")
  endforeach()
  string(APPEND prelude "rsm_texel rsm_fetch(ivec2 t) { return rsm_texel(vec3(0.0), vec3(0.0), vec3(0.0)); }\n"
                        "float rsm_depth_fetch(ivec2 t) { return 0.0; }\n"
                        "uvec4 voxel_fetch(ivec2 t) { return uvec4(0u); }\n"
                        "bilateral_tap bilateral_fetch(ivec2 t) { return bilateral_tap(vec3(0.0), 0.0, vec3(0.0)); }\n")
  # One shader holds every struct's block (member value_NAME), so that glslang runs once. It
  # reflects the members of the blocks the shader reads (all of them with
  # --reflect-all-block-variables): main reads each block's first field.
  set(blocks "")
  set(reads "0.0")
  foreach(twin ${twins})
    execute_process(COMMAND "${VPLKIT}" shader block ${twin} --member value_${twin} RESULT_VARIABLE code OUTPUT_VARIABLE block_${twin} ERROR_VARIABLE err)
    string(APPEND blocks "${block_${twin}}")
    string(REGEX MATCH "//   offset 0: ([a-z0-9_]+) ([a-zA-Z0-9_.]+)" ignored "${block_${twin}}")
    set(first "${CMAKE_MATCH_2}")
    if(CMAKE_MATCH_1 MATCHES "[234]$")
      string(APPEND first ".x")
    endif()
    string(APPEND reads " + float(${first})")
  endforeach()
  find_program(SPIRV_VAL spirv-val)
  foreach(target gl vulkan)
    if(target STREQUAL "gl")
      set(text "#version 330 core\n${prelude}${blocks}out vec4 colour;\n")
      set(options "")
    else()
      set(text "#version 450 core\n${prelude}${blocks}layout(location = 0) out vec4 colour;\n")
      set(options -V --amb -o "${WORK}/blocks.spv")
    endif()
    file(WRITE "${WORK}/blocks_${target}.frag" "${text}void main() { colour = vec4(${reads}); }\n")
    execute_process(COMMAND "${VPLKIT}" shader expand "${WORK}/blocks_${target}.frag" --shader-dir "${SHADERS}" -o "${WORK}/blocks_${target}.expanded.frag"
                    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    execute_process(COMMAND "${GLSLANG}" ${options} -l -q --reflect-all-block-variables "${WORK}/blocks_${target}.expanded.frag"
                    RESULT_VARIABLE code OUTPUT_VARIABLE reflection ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "glslangValidator failed on ${WORK}/blocks_${target}.expanded.frag: exit ${code}\n${reflection}${err}")
    endif()
    if(target STREQUAL "vulkan" AND SPIRV_VAL)
      execute_process(COMMAND "${SPIRV_VAL}" "${WORK}/blocks.spv" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
      expect_true("spirv-val: the Vulkan module of every block" code EQUAL 0)
    endif()
    set(checked 0)
    foreach(twin ${twins})
      set(block "${block_${twin}}")
      string(REGEX MATCH "in std140: ([0-9]+) bytes" ignored "${block}")
      set(size_printed "${CMAKE_MATCH_1}")
      string(FIND "${reflection}" "\n${twin}_block: offset -1, type ffffffff, size ${size_printed}," at)
      expect_true("glslang ${target}: ${twin} is ${size_printed} bytes" at GREATER -1)
      string(REGEX MATCHALL "//   offset [0-9]+: [a-z0-9_]+ [a-zA-Z0-9_.]+(\\[[0-9]+\\], stride [0-9]+)?" fields "${block}")
      foreach(field ${fields})
        string(REGEX MATCH "offset ([0-9]+): [a-z0-9_]+ ([a-zA-Z0-9_.]+)" ignored "${field}")
        set(offset ${CMAKE_MATCH_1})
        set(path ${CMAKE_MATCH_2})
        string(FIND "${reflection}" "\n${path}: offset ${offset}, " at)
        if(field MATCHES "stride ([0-9]+)$")
          set(stride ${CMAKE_MATCH_1})
          set(line "")
          if(at GREATER -1)
            string(SUBSTRING "${reflection}" ${at} 200 line)
          endif()
          expect_true("glslang ${target}: ${path} at ${offset}, stride ${stride}" at GREATER -1 AND "${line}" MATCHES "arrayStride ${stride}[,\n]")
        else()
          expect_true("glslang ${target}: ${path} at ${offset}" at GREATER -1)
        endif()
      endforeach()
      math(EXPR checked "${checked} + 1")
    endforeach()
    # Every twin the binary lists (15 when this was written: a twin that disappeared would shrink it).
    list(LENGTH twins twin_count)
    expect_true("glslang ${target}: ${twin_count} structs checked" checked EQUAL twin_count AND twin_count GREATER_EQUAL 15)
  endforeach()
endif()

cli_report()
