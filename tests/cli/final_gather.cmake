# Final gathering ([FG]): the three variants, the object near a wall, bad input.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# Final gathering ([FG]): the three variants; the object moved towards a wall; bad input.
foreach(technique finalgather-polygon finalgather-point envmap)
  expect_success("render --technique ${technique}" "technique ${technique}.*wrote .*/${technique}\\.png.*wrote .*/${technique}-indirect\\.png"
                 "${VPLKIT}" render --technique ${technique} --size 48 --face-size 32 --out "${WORK}/${technique}.png")
endforeach()
expect_success("final gathering with the object near a wall and M = 2" "at \\(0.6, 0.6, 0\\)"
               "${VPLKIT}" render --technique finalgather-polygon --object-position 0.6,0.6,0 --cube-resolution 2 --size 32 --face-size 32
               --out "${WORK}/fg-wall.png")
expect_failure("M that does not divide the face size" "M = 3 does not divide the face size 32" "${WORK}/fg1.png"
               "${VPLKIT}" render --technique finalgather-polygon --cube-resolution 3 --face-size 32 --size 32 --out "${WORK}/fg1.png")
expect_failure("reference point outside the room" "outside the room or inside geometry" "${WORK}/fg2.png"
               "${VPLKIT}" render --technique finalgather-polygon --object-position 0,0.7,5 --size 32 --face-size 32 --out "${WORK}/fg2.png")
expect_failure("object that fails to load" "${WORK}/no-object\\.obj: no such OBJ file" "${WORK}/fg3.png"
               "${VPLKIT}" render --technique finalgather-point --object "${WORK}/no-object.obj" --size 32 --out "${WORK}/fg3.png")
expect_failure("object position not a point" "--object-position.*expected x,y,z" "${WORK}/fg4.png"
               "${VPLKIT}" render --technique finalgather-point --object-position 1,2 --size 32 --out "${WORK}/fg4.png")
if(EXISTS "${WORK}/fg2.png" OR EXISTS "${WORK}/fg2-indirect.png")
  message(SEND_ERROR "FAILED final gathering: a failed render left an image behind")
  math(EXPR failures "${failures} + 1")
endif()

cli_report()
