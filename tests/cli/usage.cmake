# Usage errors: unknown options, values out of range, option scoping (an option the chosen
# technique or method does not read is an error naming it), shader folders that are missing or
# broken.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

set(H "${WORK}/hostile")
file(MAKE_DIRECTORY "${H}")
# --- bad input: a clear message, a non-zero exit, no file -------------------------------------
expect_failure("unknown option" "--bogus" "" "${VPLKIT}" render --bogus)
expect_failure("unknown subcommand" "frobnicate" "" "${VPLKIT}" frobnicate)
expect_failure("size zero" "--size.*\\[1, 16384\\]" "${WORK}/zero.png" "${VPLKIT}" render --size 0 --out "${WORK}/zero.png")
expect_failure("size not a number" "--size.*expected N or WxH" "${WORK}/bad.png" "${VPLKIT}" render --size big --out "${WORK}/bad.png")
expect_failure("negative min distance" "--min-distance" "${WORK}/md.png" "${VPLKIT}" render --min-distance -1 --out "${WORK}/md.png")
expect_failure("unknown format" "--format.*rgba8" "${WORK}/fmt.png" "${VPLKIT}" render --format rgba8 --out "${WORK}/fmt.png")
expect_failure("unknown scene" "unknown scene 'sponza'.*cornell-box.*atrium" "${WORK}/scene.png" "${VPLKIT}" render --scene sponza --out "${WORK}/scene.png")
expect_failure("unknown technique" "--technique.*rsm-alg7" "${WORK}/tech.png" "${VPLKIT}" render --technique rsm-alg7 --out "${WORK}/tech.png")
expect_failure("slots out of range" "--slots.*17" "${WORK}/slots.png" "${VPLKIT}" render --slots 17 --out "${WORK}/slots.png")
expect_failure("paths out of range" "--paths.*0" "${WORK}/paths.png" "${VPLKIT}" render --paths 0 --out "${WORK}/paths.png")
expect_failure("max radius below min radius" "max_radius must be finite and > min_radius" "${WORK}/radius.png"
               "${VPLKIT}" render --max-radius 0.5 --out "${WORK}/radius.png")
expect_failure("RSM size out of range" "--rsm-size.*16385" "${WORK}/big.png"
               "${VPLKIT}" render --size 8 --rsm-size 16385 --out "${WORK}/big.png")
# 3 targets of 16384^2 rgba16f: 6 GiB, more than llvmpipe allocates (or above GL_MAX_TEXTURE_SIZE elsewhere).
expect_failure("RSM too large for the GL implementation" "16384x16384 rgba32ui texture" "${WORK}/big.png"
               "${VPLKIT}" render --size 8 --rsm-size 16384 --out "${WORK}/big.png")
expect_failure("output not a png" "--out must name a \\.png file" "${WORK}/image.jpg" "${VPLKIT}" render --out "${WORK}/image.jpg")
file(WRITE "${WORK}/a-file" "")
expect_failure("unwritable output path" "cannot write ${WORK}/a-file/x\\.png" "${WORK}/a-file/x.png"
               "${VPLKIT}" render --size 16 --out "${WORK}/a-file/x.png")
expect_failure("missing shader folder" "shader directory not found: ${WORK}/no-shaders" "${WORK}/ns.png"
               "${VPLKIT}" render --shader-dir "${WORK}/no-shaders" --out "${WORK}/ns.png")

# A shader folder with one file missing, and one with a syntax error in a lib file.
file(COPY "${SHADERS}/" DESTINATION "${WORK}/missing-file")
file(REMOVE "${WORK}/missing-file/gather.frag")
expect_failure("missing shader file" "shader file not found: ${WORK}/missing-file/gather\\.frag" "${WORK}/mf.png"
               "${VPLKIT}" render --shader-dir "${WORK}/missing-file" --out "${WORK}/mf.png")
file(COPY "${SHADERS}/" DESTINATION "${WORK}/syntax-error")
file(READ "${WORK}/syntax-error/lib/direct_light.glsl" text)
set(marker "return t * t * (3.0 - 2.0 * t);")
string(FIND "${text}" "${marker}" offset)
string(SUBSTRING "${text}" 0 ${offset} before)
string(REGEX MATCHALL "\n" newlines "${before}")
list(LENGTH newlines line)
math(EXPR line "${line} + 1")  # the 1-based line of the marker
string(REPLACE "${marker}" "return t * t * (3.0 - 2.0 * t) +;" text "${text}")
file(WRITE "${WORK}/syntax-error/lib/direct_light.glsl" "${text}")
expect_failure("GLSL syntax error names the lib file and line" "GLSL compile error.*lib/direct_light\\.glsl:${line}:" "${WORK}/se.png"
               "${VPLKIT}" render --shader-dir "${WORK}/syntax-error" --out "${WORK}/se.png")
# Mesa prints source number 0 for an undeclared name, whatever file it is in: the message named
# the top-level rsm.frag at direct_light.glsl's line.
file(COPY "${SHADERS}/" DESTINATION "${WORK}/undeclared")
string(REPLACE "return t * t * (3.0 - 2.0 * t) +;" "return t * t * (3.0 - 2.0 * t) + undeclared_thing;" text "${text}")
file(WRITE "${WORK}/undeclared/lib/direct_light.glsl" "${text}")
expect_failure("GLSL undeclared name names the lib file and line" "GLSL compile error[^\n]*\n  lib/direct_light\\.glsl:${line}:[0-9]+: error: .undeclared_thing. undeclared"
               "${WORK}/ud.png" "${VPLKIT}" render --shader-dir "${WORK}/undeclared" --out "${WORK}/ud.png")

expect_failure("both --radius and --max-radius" "--max-radius and --radius set the same setting: give one of them" "${WORK}/r2.png"
               "${VPLKIT}" render --radius 0.5 --max-radius 30 --size 16 --rsm-size 32 --out "${WORK}/r2.png")
foreach(bad 0 nan -1 3 inf)
  expect_failure("--radius ${bad}" "--radius.*must be a number in \\(0, 2\\]" "${WORK}/r3.png"
                 "${VPLKIT}" render --radius ${bad} --size 16 --rsm-size 32 --out "${WORK}/r3.png")
endforeach()
expect_failure("--preset that does not exist" "--preset.*must be default or thesis, got 'fast'" "${WORK}/r4.png" "${VPLKIT}" render --preset fast --size 16 --out "${WORK}/r4.png")
expect_failure("--visibility of the Monte Carlo reference" "--visibility is read by --method rsm-brute-force, not by method monte-carlo" "${WORK}/mc.pfm"
               "${VPLKIT}" reference --visibility none --size 16 --out "${WORK}/mc.pfm")
expect_failure("--samples of the brute-force reference" "--samples is read by --method monte-carlo, not by method rsm-brute-force" "${WORK}/bf2.pfm"
               "${VPLKIT}" reference --method rsm-brute-force --samples 4 --size 16 --out "${WORK}/bf2.pfm")
expect_failure("--raw-indirect without indirect light" "--raw-indirect is read by rsm-original, rsm-radial, rsm-alg2, rsm-alg3, rsm-alg6, rsm-alg6-ray and rsm-voxel \\(the techniques that gather indirect light\\), not by technique direct" "${WORK}/direct-raw.png"
               "${VPLKIT}" render --technique direct --raw-indirect --size 16 --rsm-size 32 --out "${WORK}/direct-raw.png")
if(EXISTS "${WORK}/direct-raw-indirect.pfm")
  message(SEND_ERROR "FAILED --raw-indirect without indirect light: left ${WORK}/direct-raw-indirect.pfm behind")
  math(EXPR failures "${failures} + 1")
endif()

# Options are scoped: each subcommand declares only what it reads, and an option that the chosen
# technique or method does not read is an error naming it (exit 2), never silently ignored.
expect_failure("reference declares no technique options" "not expected: .*--object.*--cube-resolution.*--paths.*--technique"
               "${WORK}/scoped-reference.pfm"
               "${VPLKIT}" reference --technique lightwave-accurate --paths 3 --cube-resolution 7 --object missing.obj --out "${WORK}/scoped-reference.pfm")
# Every technique reads --scene (final gathering gathers in it around its object): an open scene
# (the teapot on its floor) leaves the cube map seeing the void, refused by name.
expect_failure("final gathering in an open scene" "reference point \\(0\\.0+, 0\\.70+, 0\\.0+\\).*outside the room or inside geometry"
               "${WORK}/scoped-fg*.png" "${VPLKIT}" render --technique finalgather-polygon --scene teapot --size 32 --face-size 32 --out "${WORK}/scoped-fg.png")
expect_failure("an RSM technique reads no Light Wave option" "--ray-angle is read by lightwave-unshadowed, lightwave-accurate and lightwave-integrated \\(the VPL light\\), not by technique rsm-alg6"
               "${WORK}/scoped-rsm.png" "${VPLKIT}" render --technique rsm-alg6 --ray-angle 10 --out "${WORK}/scoped-rsm.png")
expect_failure("--faked-multiplier is lightwave-faked's" "--faked-multiplier is read by lightwave-faked \\(the faked indirect light\\), not by technique lightwave-accurate"
               "${WORK}/scoped-lw.png" "${VPLKIT}" render --technique lightwave-accurate --faked-multiplier 1.2 --out "${WORK}/scoped-lw.png")
expect_failure("--slots needs the micro linear buffer" "--slots is read by rsm-alg2, rsm-alg3, rsm-alg6 and rsm-alg6-ray \\(the micro linear buffer\\), not by technique rsm-radial"
               "${WORK}/scoped-slots.png" "${VPLKIT}" render --technique rsm-radial --slots 4 --out "${WORK}/scoped-slots.png")
expect_failure("Light Wave reads no --object" "--object is read by finalgather-polygon, finalgather-point and envmap, not by technique lightwave-direct"
               "${WORK}/scoped-object.png" "${VPLKIT}" render --technique lightwave-direct --object sphere --out "${WORK}/scoped-object.png")
expect_failure("the Monte Carlo reference reads no --min-distance" "--min-distance is read by --method rsm-brute-force, not by method monte-carlo"
               "${WORK}/scoped-mc.pfm" "${VPLKIT}" reference --min-distance 0.1 --out "${WORK}/scoped-mc.pfm")

# 8. Light Wave and other numeric options: non-finite and out-of-range values.
expect_failure("--shadow-map-scale nan" "--shadow-map-scale.*\\(0, 16\\]" "${H}/out*" "${VPLKIT}" render --technique lightwave-accurate --shadow-map-scale nan --out "${H}/out.png")
expect_failure("--vpl-max-distance inf" "--vpl-max-distance.*\\[0, 10000000\\]" "${H}/out*" "${VPLKIT}" render --technique lightwave-accurate --vpl-max-distance inf --out "${H}/out.png")
expect_failure("--error-scale nan" "--error-scale.*must be a number" "${H}/out*" "${VPLKIT}" compare "${H}/kd-zero.pfm" "${H}/kd-zero.pfm" --error-scale nan --error-image "${H}/out.png")
expect_failure("--object-size 1e30" "--object-size.*\\(0, 10\\]" "${H}/out*" "${VPLKIT}" render --technique finalgather-point --object-size 1e30 --out "${H}/out.png")

cli_report()
