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
foreach(technique direct rsm-original rsm-radial rsm-alg2 rsm-alg3 rsm-alg6)
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

cli_report()
