# The RSM techniques of [RSMV]: every technique renders, OBJ scenes, the brute-force reference of
# the same frame, presets.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

expect_success("render writes the images and says where"
               "wrote .*/small\\.png.*wrote .*/small-indirect\\.png.*wrote .*/small-visibility-difference\\.png"
               "${VPLKIT}" render --size 48x32 --rsm-size 64 --out "${WORK}/small.png")
foreach(image small small-indirect small-visibility-difference)
  if(NOT EXISTS "${WORK}/${image}.png")
    message(SEND_ERROR "FAILED render: ${WORK}/${image}.png does not exist")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
expect_success("render prints the pass table of Table 5.3"
               "\\| RSM generation \\|.*\\| G-buffer generation \\|.*\\| RSM sampling \\|.*\\| post processing \\|.*\\| total \\|"
               "${VPLKIT}" render --size 16 --rsm-size 32 --format rgba32f --out "${WORK}/f32.png")
foreach(technique direct rsm-original rsm-radial rsm-alg2 rsm-alg3 rsm-alg6 rsm-alg6-ray rsm-voxel)
  expect_success("render --technique ${technique}" "technique ${technique}"
                 "${VPLKIT}" render --technique ${technique} --scene indirect-shadow --size 24 --rsm-size 32
                 --out "${WORK}/t-${technique}.png")
endforeach()
if(EXISTS "${WORK}/t-direct-indirect.png" OR EXISTS "${WORK}/t-rsm-radial-visibility-difference.png")
  message(SEND_ERROR "FAILED render: an indirect or difference image for a technique without one")
  math(EXPR failures "${failures} + 1")
endif()

# A malformed OBJ scene: named with file:line, nothing written.
file(WRITE "${WORK}/bad.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
expect_failure("malformed OBJ scene" "${WORK}/bad\\.obj:4: face vertex index 9 is out of range" "${WORK}/obj.png"
               "${VPLKIT}" render --scene "${WORK}/bad.obj" --size 16 --out "${WORK}/obj.png")
expect_failure("missing OBJ scene" "${WORK}/none\\.obj: no such OBJ file" "${WORK}/none.png"
               "${VPLKIT}" render --scene "${WORK}/none.obj" --size 16 --out "${WORK}/none.png")
file(WRITE "${WORK}/good.obj" "v -1 0 -1\nv 1 0 -1\nv 0 1 0\nf 1 2 3\n")
expect_success("an OBJ scene renders" "scene good \\(3 triangles\\)" "${VPLKIT}" render --scene "${WORK}/good.obj" --size 16 --rsm-size 32
               --out "${WORK}/good.png")

# The RSM gather against its brute-force reference of the same frame (issue 9).
expect_success("render writes the linear indirect PFMs, filtered and raw"
               "wrote .*/bf-frame-indirect\\.pfm.*wrote .*/bf-frame-raw-indirect\\.pfm"
               "${VPLKIT}" render --scene occluder --size 32 --rsm-size 32 --raw-indirect --out "${WORK}/bf-frame.png")
foreach(visibility exact none)
  expect_success("reference --method rsm-brute-force --visibility ${visibility}"
                 "brute-force RSM gather.*16x16 receivers.*wrote .*/bf-${visibility}\\.pfm.*wrote .*/bf-${visibility}\\.png.*wrote .*/bf-${visibility}-receivers\\.pfm"
                 "${VPLKIT}" reference --method rsm-brute-force --visibility ${visibility} --scene occluder --size 32 --rsm-size 32
                 --out "${WORK}/bf-${visibility}.pfm")
endforeach()
expect_success("compare the raw gather with the brute force over the covered receivers"
               "relative RMSE \\(RMSE / reference mean\\) \\| [0-9.e-]+ \\|.*relative bias.*masked relative RMSE \\([0-9]+ pixels\\) \\| [0-9.e-]+ \\|.*masked relative bias"
               "${VPLKIT}" compare "${WORK}/bf-frame-raw-indirect.pfm" "${WORK}/bf-none.pfm" --mask "${WORK}/bf-none-receivers.pfm")
expect_success("render --preset thesis" "technique rsm-alg6" "${VPLKIT}" render --preset thesis --size 16 --rsm-size 32 --out "${WORK}/thesis.png")
expect_success("render --radius and --slots override the preset" "technique rsm-alg6"
               "${VPLKIT}" render --preset thesis --radius 0.9 --slots 7 --size 16 --rsm-size 32 --out "${WORK}/radius.png")
file(MAKE_DIRECTORY "${WORK}/blocked-receivers.pfm")
expect_failure("brute-force reference whose mask cannot be written leaves nothing" "blocked-receivers\\.pfm" "${WORK}/blocked.pfm"
               "${VPLKIT}" reference --method rsm-brute-force --size 16 --rsm-size 16 --out "${WORK}/blocked.pfm")
if(EXISTS "${WORK}/blocked.png")
  message(SEND_ERROR "FAILED brute-force reference: a failed write left blocked.png behind")
  math(EXPR failures "${failures} + 1")
endif()

# Coverage, the original RSM's weights and the brute force over every receiver (issue 23).
expect_success("render --coverage-blocks 0 (the pattern alone) and --disk-weights printed" "technique rsm-original"
               "${VPLKIT}" render --technique rsm-original --disk-weights printed --coverage-blocks 0 --size 16 --rsm-size 32 --out "${WORK}/printed.png")
expect_failure("--coverage-interleave beyond the post filter's reach" "coverage-interleave 8 needs a post filter of at least 17 taps" ""
               "${VPLKIT}" render --coverage-interleave 8 --filter-kernel-size 9 --size 16 --out "${WORK}/nothing.png")
# --disk-pattern: the setting in effect says which, and the two patterns gather differently.
foreach(pattern fixed per-pixel)
  expect_success("--disk-pattern ${pattern}" "technique rsm-original"
                 "${VPLKIT}" render --technique rsm-original --disk-pattern ${pattern} --scene cornell-box --size 32 --rsm-size 32
                 --stats "${WORK}/disk-${pattern}.json" --out "${WORK}/disk-${pattern}.png")
  file(READ "${WORK}/disk-${pattern}.json" disk_stats)
  if(NOT disk_stats MATCHES "\"disk-pattern\": \"${pattern}\"")
    message(SEND_ERROR "FAILED --disk-pattern ${pattern}: the stats' settings do not say \"disk-pattern\": \"${pattern}\"")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
file(SHA256 "${WORK}/disk-fixed-indirect.pfm" fixed_hash)
file(SHA256 "${WORK}/disk-per-pixel-indirect.pfm" per_pixel_hash)
if(fixed_hash STREQUAL per_pixel_hash)
  message(SEND_ERROR "FAILED --disk-pattern: fixed and per-pixel wrote the same indirect light")
  math(EXPR failures "${failures} + 1")
endif()
expect_failure("--disk-pattern is rsm-original's" "--disk-pattern is read by rsm-original \\(the original RSM.s disk\\), not by technique rsm-radial" ""
               "${VPLKIT}" render --technique rsm-radial --disk-pattern fixed --size 16 --out "${WORK}/nothing.png")
expect_failure("--disk-weights is rsm-original's" "--disk-weights is read by rsm-original \\(the original RSM.s disk\\), not by technique rsm-alg6" ""
               "${VPLKIT}" render --disk-weights printed --size 16 --out "${WORK}/nothing.png")
expect_success("reference --receivers all counts every receiver with a surface, covered marks the pattern's"
               "16x16 receivers.*with a surface.*covered by the pattern.*-receivers\\.pfm marks the covered ones"
               "${VPLKIT}" reference --method rsm-brute-force --visibility none --receivers covered --scene cornell-box --size 32 --rsm-size 32
               --out "${WORK}/bf-covered.pfm")
expect_success("reference --receivers all (the default)" "-receivers\\.pfm marks every one with a surface"
               "${VPLKIT}" reference --method rsm-brute-force --visibility none --scene cornell-box --size 32 --rsm-size 32 --out "${WORK}/bf-all.pfm")

# Sequences: render --poses (issue 23). One pipeline renders every line; frame k equals a render
# started at frame k's poses (without accumulation, and the first frame with it).
file(WRITE "${WORK}/poses.txt" "# a light move, a camera move, both\n--light 0.2,1.9,0.1,0,0,0\n\n--camera 0.5,1,3.5,0,1,0  # look from the right\n"
                               "--light -0.2,1.9,0,0,0,0 --camera 0,1.2,3.6,0,0.9,0\n")
expect_success("render --poses writes a numbered frame per line"
               "3 frames from .*wrote .*/seq-0001\\.png.*wrote .*/seq-0001-indirect\\.pfm.*wrote .*/seq-0003\\.png.*wrote .*/seq-0003-indirect\\.pfm"
               "${VPLKIT}" render --poses "${WORK}/poses.txt" --temporal-blend 1 --size 24 --rsm-size 32 --out "${WORK}/seq.png")
expect_success("the third frame's poses as one render" "technique rsm-alg6"
               "${VPLKIT}" render --light -0.2,1.9,0,0,0,0 --camera 0,1.2,3.6,0,0.9,0 --size 24 --rsm-size 32 --out "${WORK}/third.png")
compare_within("frame 3 of a sequence equals a render at its poses" "${WORK}/seq-0003-indirect.pfm" "${WORK}/third-indirect.pfm" 0)
expect_success("render --poses with temporal accumulation (the default)" "3 frames"
               "${VPLKIT}" render --poses "${WORK}/poses.txt" --size 24 --rsm-size 32 --out "${WORK}/acc.png")
expect_success("the first frame's poses as one render" "technique rsm-alg6"
               "${VPLKIT}" render --light 0.2,1.9,0.1,0,0,0 --size 24 --rsm-size 32 --out "${WORK}/first.png")
compare_within("the first accumulated frame has no history: a render at its poses" "${WORK}/acc-0001-indirect.pfm" "${WORK}/first-indirect.pfm" 0)
file(WRITE "${WORK}/bad-poses.txt" "--light 0.2,1.9,0.1,0,0,0\n--size 32\n")
expect_failure("a pose file with another option names the line" "bad-poses\\.txt:2: expected --camera or --light, got '--size'" "${WORK}/bad-*.png"
               "${VPLKIT}" render --poses "${WORK}/bad-poses.txt" --size 16 --rsm-size 16 --out "${WORK}/bad.png")
file(WRITE "${WORK}/up-poses.txt" "--light 0.2,1.9,0.1,0,0,0\n--camera 0,1,3,0,1,3\n")
expect_failure("a pose file with an impossible pose names the line" "up-poses\\.txt:2: --camera" "${WORK}/up-0*"
               "${VPLKIT}" render --poses "${WORK}/up-poses.txt" --size 16 --rsm-size 16 --out "${WORK}/up.png")
file(WRITE "${WORK}/along-up.txt" "--light 0.2,1.9,0.1,0,0,0\n--camera 0,1,3,0,2,3\n")
expect_failure("a camera looking along its up vector on line 2 leaves no frame behind" "along-up\\.txt:2: --camera: the camera looks along its up vector"
               "${WORK}/along*.p*" "${VPLKIT}" render --poses "${WORK}/along-up.txt" --size 16 --rsm-size 16 --out "${WORK}/along.png")
expect_failure("--temporal-blend needs --poses" "--temporal-blend is read with --poses" ""
               "${VPLKIT}" render --temporal-blend 0.5 --size 16 --out "${WORK}/nothing.png")
expect_failure("--poses is the RSM techniques'" "--poses is read by the RSM techniques \\(direct, rsm-\\*\\), not by technique lightwave-direct" ""
               "${VPLKIT}" render --technique lightwave-direct --poses "${WORK}/poses.txt" --out "${WORK}/nothing.png")
expect_failure("a missing pose file" "none\\.txt" "${WORK}/none-*"
               "${VPLKIT}" render --poses "${WORK}/none.txt" --size 16 --out "${WORK}/none.png")

# --max-seconds (issue 36): a sequence of 20,000 tiny frames (minutes) with 1 s stops after the
# frame during which the second ran out, writes frames 1 to k whole, says so, and exits 3.
string(REPEAT "--light 0.2,1.9,0.1,0,0,0\n--camera 0.5,1,3.5,0,1,0\n" 500 thousand_poses)
file(WRITE "${WORK}/long-poses.txt" "")
foreach(block RANGE 1 20)
  file(APPEND "${WORK}/long-poses.txt" "${thousand_poses}")
endforeach()
execute_process(COMMAND "${VPLKIT}" render --poses "${WORK}/long-poses.txt" --size 8 --rsm-size 8 --max-seconds 1 --out "${WORK}/cut.png"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(written 0)
if(err MATCHES "stopped by --max-seconds 1 after [0-9]+ s: wrote frames 1 to ([0-9]+) of 20000; the other [0-9]+ were not rendered \\(exit code 3\\)")
  set(written ${CMAKE_MATCH_1})
endif()
math(EXPR next "${written} + 1")
string(LENGTH "${written}" digits)
math(EXPR zeros "5 - ${digits}")
string(REPEAT "0" ${zeros} padding)
string(LENGTH "${next}" digits)
math(EXPR zeros "5 - ${digits}")
string(REPEAT "0" ${zeros} next_padding)
file(GLOB cut_files "${WORK}/cut-*")
list(LENGTH cut_files cut_count)
math(EXPR expected_files "3 * ${written}")  # .png, -indirect.pfm and -direct.pfm per frame
expect_true("render --poses --max-seconds 1 of 20,000 frames: exit 3 (${code}), frames 1 to ${written} written whole, none after (${cut_count} files): ${err}"
            code EQUAL 3 AND written GREATER 0 AND written LESS 20000 AND cut_count EQUAL expected_files
            AND EXISTS "${WORK}/cut-${padding}${written}.png" AND EXISTS "${WORK}/cut-${padding}${written}-indirect.pfm"
            AND EXISTS "${WORK}/cut-${padding}${written}-direct.pfm"
            AND NOT EXISTS "${WORK}/cut-${next_padding}${next}.png" AND out MATCHES "\n${written} frames from .*wrote .*/cut-00001\\.png")
expect_failure("--max-seconds bounds a sequence" "--max-seconds bounds a --poses sequence, not one frame" "${WORK}/one.png"
               "${VPLKIT}" render --max-seconds 5 --size 16 --out "${WORK}/one.png")
expect_failure("--max-seconds is a number of seconds" "--max-seconds: must be a number in \\[0, 1e\\+09\\]" "${WORK}/neg-*"
               "${VPLKIT}" render --poses "${WORK}/poses.txt" --max-seconds -1 --size 16 --out "${WORK}/neg.png")

cli_report()
