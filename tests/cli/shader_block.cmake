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
               "no settings struct .no_such_settings. has a GLSL twin \\(known: irradiance_settings, radial_pattern_constants, .*, temporal_settings\\)" ""
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

cli_report()
