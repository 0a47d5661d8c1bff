# Ground truth: the Monte Carlo reference and `vplkit compare`.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# The images this part compares: a 48x32 render, a malformed and a good OBJ.
expect_success("render a 48x32 image" "wrote" "${VPLKIT}" render --size 48x32 --rsm-size 64 --out "${WORK}/small.png")
file(WRITE "${WORK}/bad.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
file(WRITE "${WORK}/good.obj" "v -1 0 -1\nv 1 0 -1\nv 0 1 0\nf 1 2 3\n")
set(H "${WORK}/hostile")
file(MAKE_DIRECTORY "${H}")
# Ground truth: the reference renderer and the comparison (issue 6).
expect_success("reference writes PFM and PNG" "wrote .*/ref\\.pfm.*wrote .*/ref-indirect\\.pfm.*wrote .*/ref\\.png"
               "${VPLKIT}" reference --size 24 --samples 8 --out "${WORK}/ref.pfm")
expect_success("compare an image with itself" "\\| RMSE \\| 0 \\|.*\\| similarity \\(Alg. 1, %\\) \\| 100 \\|"
               "${VPLKIT}" compare "${WORK}/ref.pfm" "${WORK}/ref.pfm")
expect_success("compare with a mask and an error image" "masked RMSE.*masked relative RMSE.*wrote .*/err\\.png"
               "${VPLKIT}" compare "${WORK}/ref.png" "${WORK}/ref.pfm" --mask "${WORK}/ref.pfm" --error-image "${WORK}/err.png")
# Against a black reference (direct light's indirect image is 0 everywhere) the relative numbers
# and PSNR are undefined, with the reason; they once read 0, a perfect score. The absolute
# ones stay numbers.
expect_success("direct light: a black indirect image" "wrote .*/direct-indirect\\.pfm" "${VPLKIT}" render --technique direct --size 24 --out "${WORK}/direct.png")
expect_success("compare against a black reference: the relative numbers are undefined, and why"
               "\\| RMSE \\| [0-9.]+ \\|.*\\| PSNR \\(dB\\) \\| undefined: the reference is black.*\\| relative RMSE \\(RMSE / reference mean\\) \\| undefined: the reference's mean is 0 \\(black\\) over the 576 pixels.*\\| relative bias [^|]*\\| undefined: the reference's mean is 0 \\(black\\).*\\| masked relative RMSE \\([0-9]+ pixels\\) \\| undefined: the reference's mean is 0 \\(black\\) over the [0-9]+ masked pixels"
               "${VPLKIT}" compare "${WORK}/ref.pfm" "${WORK}/direct-indirect.pfm" --mask "${WORK}/ref.pfm")
execute_process(COMMAND "${VPLKIT}" compare "${WORK}/ref.pfm" "${WORK}/direct-indirect.pfm" OUTPUT_VARIABLE out)
expect_true("no relative number reads 0 against a black reference" NOT out MATCHES "relative (RMSE|bias)[^\n]*[|] 0 [|]")
expect_true("nor does the share of lit pixels darker than half: the reference has none"
            out MATCHES "[|] lit pixels darker than half the reference [(]%[)] [|] undefined: the reference has no lit pixel [|]")
expect_failure("compare images of different sizes" "the image ${WORK}/ref\\.pfm is 24x24 but the reference ${WORK}/small\\.png is 48x32" "${WORK}/err2.png"
               "${VPLKIT}" compare "${WORK}/ref.pfm" "${WORK}/small.png" --error-image "${WORK}/err2.png")
expect_failure("compare an unreadable file" "${WORK}/missing\\.pfm: no such PFM image" "" "${VPLKIT}" compare "${WORK}/missing.pfm" "${WORK}/ref.pfm")
file(WRITE "${WORK}/bad.pfm" "P6 garbage")
expect_failure("compare a malformed PFM" "bad\\.pfm: not an RGB PFM file" "" "${VPLKIT}" compare "${WORK}/bad.pfm" "${WORK}/ref.pfm")
expect_failure("compare an unsupported format" "unsupported image format '.obj'" "" "${VPLKIT}" compare "${WORK}/good.obj" "${WORK}/ref.pfm")
expect_failure("reference of a scene it cannot load" "bad\\.obj:4: face vertex index 9" "${WORK}/bad-ref.pfm"
               "${VPLKIT}" reference --scene "${WORK}/bad.obj" --size 16 --out "${WORK}/bad-ref.pfm")
expect_failure("reference output not a .pfm" "--out must name a .pfm file" "" "${VPLKIT}" reference --size 16 --out "${WORK}/ref.png")

# 9. A multi-file output with one file blocked: nothing written, and the reason (not "Success").
file(MAKE_DIRECTORY "${H}/blocked-indirect.pfm")
expect_failure("reference: one output blocked by a folder" "cannot write .*blocked-indirect\\.pfm: a folder of that name is in the way" "${H}/blocked.pfm"
               "${VPLKIT}" reference --size 16 --samples 1 --out "${H}/blocked.pfm")
if(EXISTS "${H}/blocked.png")
  message(SEND_ERROR "FAILED reference: a blocked output left blocked.png behind")
  math(EXPR failures "${failures} + 1")
endif()
# 10. compare: sizes named with their files; an error image that is an input.
expect_failure("compare: --error-image is an input" "--error-image .*kd-zero-copy\\.png is the input" "${H}/out*"
               "${VPLKIT}" compare "${WORK}/ref.png" "${H}/kd-zero-copy.png" --error-image "${H}/./kd-zero-copy.png")
file(SHA256 "${WORK}/ref.png" before)
expect_failure("compare: --error-image is the image itself" "is the input" "${H}/out*" "${VPLKIT}" compare "${WORK}/ref.png" "${WORK}/ref.png" --error-image "${WORK}/ref.png")
file(SHA256 "${WORK}/ref.png" after)
if(NOT before STREQUAL after)
  message(SEND_ERROR "FAILED compare: --error-image overwrote its input")
  math(EXPR failures "${failures} + 1")
endif()

# 11. Long work announced and bounded (issue 26): 512^2 x 2^20 samples, refused by its estimate at
# once (the run itself would take about a day), and the cost printed first.
execute_process(COMMAND "${VPLKIT}" reference --size 512 --samples 1048576 --max-seconds 10 --out "${H}/day.pfm" RESULT_VARIABLE code ERROR_VARIABLE err)
expect_true("reference: a day of work against --max-seconds 10 is refused before it starts (exit ${code}: ${err})"
            code EQUAL 1 AND err MATCHES "^vplkit reference: 262144 pixels x .*: at most 5[.]5e[+]11 rays, estimated [0-9.]+ (h|days) on"
            AND err MATCHES "exceeds --max-seconds 10. nothing is written" AND NOT EXISTS "${H}/day.pfm")
execute_process(COMMAND "${VPLKIT}" reference --method rsm-brute-force --size 32 --rsm-size 32 --out "${H}/brute.pfm" RESULT_VARIABLE code ERROR_VARIABLE err)
expect_true("reference: the brute force announces its cost (exit ${code}: ${err})"
            code EQUAL 0 AND err MATCHES "^vplkit reference: [0-9]+ receivers x [0-9]+ lit RSM texels, a shadow ray per pair with light: at most [0-9.e+]+ rays, estimated"
            AND EXISTS "${H}/brute.pfm")
expect_failure("reference --max-seconds -1" "--max-seconds: must be a number in \\[0, 1e\\+09\\]" "" "${VPLKIT}" reference --max-seconds -1 --out "${H}/x.pfm")


# 12. The direct light (issue 38): render's -direct.pfm against the Monte Carlo reference's, the
# ray-traced direct light with exact shadow rays, for a spot, a point light and a sun in the
# Cornell box (exported, two lights added: a point light under the ceiling, a sun through the
# open front). The same quantity (shadowed direct irradiance), so the image means agree within a
# few % and at most 2 % of the lit pixels are darker than half the reference: a missing cube face,
# a seam between faces, shadow acne or a sun's shadow map that misses the room each fail it.
expect_success("export the Cornell box" "wrote" "${VPLKIT}" export-scene cornell-box "${WORK}/lights.gltf")
file(READ "${WORK}/lights.gltf" box)
string(JSON count LENGTH "${box}" nodes)
string(JSON box SET "${box}" extensions KHR_lights_punctual lights 1 [=[{"type": "point", "color": [1.0, 0.9, 0.8], "intensity": 2.0}]=])
string(JSON box SET "${box}" extensions KHR_lights_punctual lights 2 [=[{"type": "directional", "color": [0.9, 0.95, 1.0], "intensity": 3.0}]=])
string(JSON box SET "${box}" nodes ${count} [=[{"name": "bulb", "translation": [0.35, 1.55, 0.25], "extensions": {"KHR_lights_punctual": {"light": 1}}}]=])
math(EXPR count "${count} + 1")
string(JSON box SET "${box}" nodes ${count} [=[{"name": "sun", "rotation": [-0.2237149, -0.134229, 0.0, 0.9653674], "extensions": {"KHR_lights_punctual": {"light": 2}}}]=])
string(JSON scene_nodes LENGTH "${box}" scenes 0 nodes)
math(EXPR bulb "${count} - 1")
string(JSON box SET "${box}" scenes 0 nodes ${scene_nodes} ${bulb})
math(EXPR scene_nodes "${scene_nodes} + 1")
string(JSON box SET "${box}" scenes 0 nodes ${scene_nodes} ${count})
file(WRITE "${WORK}/lights.gltf" "${box}")

# direct_matches(<name> <image> <reference>): relative bias within +-4 % and at most 2 % of the lit
# pixels darker than half the reference.
function(direct_matches name candidate reference)
  execute_process(COMMAND "${VPLKIT}" compare "${candidate}" "${reference}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCH "\\| relative bias [^|]*\\| ([0-9.e+-]+) \\|" found_bias "${out}")
  set(bias "${CMAKE_MATCH_1}")
  string(REGEX MATCH "\\| lit pixels darker than half the reference \\(%\\) \\| ([0-9.e+-]+) \\(" found_darker "${out}")
  set(darker "${CMAKE_MATCH_1}")
  if(code EQUAL 0 AND found_bias AND found_darker AND bias GREATER_EQUAL -0.04 AND bias LESS_EQUAL 0.04 AND darker LESS_EQUAL 2)
    message(STATUS "ok ${name}: relative bias ${bias}, ${darker} % of the lit pixels darker than half")
  else()
    message(SEND_ERROR "FAILED ${name}: relative bias '${bias}' (bound +-0.04), darker than half '${darker}' % (bound 2), exit ${code}\n  ${out}${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  endif()
endfunction()

foreach(light 0 1 2)
  set(kind_0 spot)
  set(kind_1 point)
  set(kind_2 sun)
  set(kind ${kind_${light}})
  expect_success("the ray-traced direct light, ${kind}" "wrote .*/mc-${kind}-direct\\.pfm" "${VPLKIT}" reference --scene "${WORK}/lights.gltf" --lights ${light}
                 --size 64 --samples 1 --out "${WORK}/mc-${kind}.pfm")
  expect_success("the RSM pipeline's direct light, ${kind}" "wrote .*/rsm-${kind}-direct\\.pfm" "${VPLKIT}" render --scene "${WORK}/lights.gltf" --lights ${light}
                 --technique direct --size 64 --rsm-size 256 --out "${WORK}/rsm-${kind}.png")
  direct_matches("RSM direct light, ${kind}: the ray-traced direct light" "${WORK}/rsm-${kind}-direct.pfm" "${WORK}/mc-${kind}-direct.pfm")
endforeach()
# A gathering technique writes the same direct light as direct light only (the post pass adds
# its indirect light apart), and the Light Wave and final-gathering pipelines write theirs for
# every kind of light too (each their own shadow maps: a spot's frustum, a point light's six
# faces, a sun's orthographic map; final gathering's object made a speck in a corner, which the
# reference does not hold).
expect_success("rsm-alg6's direct light" "wrote" "${VPLKIT}" render --scene "${WORK}/lights.gltf" --lights 0 --technique rsm-alg6 --size 64 --rsm-size 256
               --out "${WORK}/alg6-spot.png")
compare_within("rsm-alg6's direct light is direct light only's" "${WORK}/alg6-spot-direct.pfm" "${WORK}/rsm-spot-direct.pfm" 1e-6)
foreach(light 0 1 2)
  set(kind ${kind_${light}})
  expect_success("Light Wave's direct light, ${kind}" "wrote .*/lw-${kind}-direct\\.pfm" "${VPLKIT}" render --scene "${WORK}/lights.gltf" --lights ${light}
                 --technique lightwave-direct --size 64 --out "${WORK}/lw-${kind}.png")
  direct_matches("Light Wave direct light, ${kind}: the ray-traced direct light" "${WORK}/lw-${kind}-direct.pfm" "${WORK}/mc-${kind}-direct.pfm")
  expect_success("final gathering's direct light, ${kind}" "wrote .*/fg-${kind}-direct\\.pfm" "${VPLKIT}" render --scene "${WORK}/lights.gltf" --lights ${light}
                 --technique finalgather-point --size 64 --object-at 0.9,0,-0.9,0.02 --out "${WORK}/fg-${kind}.png")
  direct_matches("final gathering direct light, ${kind}: the ray-traced direct light" "${WORK}/fg-${kind}-direct.pfm" "${WORK}/mc-${kind}-direct.pfm")
endforeach()
# All or nothing: a -direct.pfm that cannot be written (a folder in its place) leaves no file of
# the set, for render and for the reference.
file(MAKE_DIRECTORY "${H}/dblocked-direct.pfm")
expect_failure("render: -direct.pfm blocked by a folder" "cannot write .*dblocked-direct\\.pfm: a folder of that name is in the way" "${H}/dblocked.p*"
               "${VPLKIT}" render --size 16 --rsm-size 16 --out "${H}/dblocked.png")
expect_true("render: nor its -indirect.pfm" NOT EXISTS "${H}/dblocked-indirect.pfm")
expect_failure("reference: -direct.pfm blocked by a folder" "cannot write .*dblocked-direct\\.pfm: a folder of that name is in the way" "${H}/dblocked.p*"
               "${VPLKIT}" reference --size 16 --samples 1 --out "${H}/dblocked.pfm")
expect_true("reference: nor its -indirect.pfm" NOT EXISTS "${H}/dblocked-indirect.pfm")

cli_report()
