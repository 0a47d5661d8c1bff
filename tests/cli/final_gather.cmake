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

# In the user's scene (--scene): a glTF room of bench/scenes (its spot, its camera) with an OBJ
# object the test writes (a tetrahedron), near a wall and in the open; the Monte Carlo reference
# of the object's indirect light in the same scene; the refusals.
set(room "${FUZZ_INPUTS}/../../../bench/scenes/room-a.gltf")
file(WRITE "${WORK}/tetra.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
foreach(technique finalgather-polygon finalgather-point envmap)
  expect_success("render --technique ${technique} --scene room-a.gltf" "object tetra .*at \\(-2, 1.2, 1\\).*wrote .*/room-${technique}\\.png"
                 "${VPLKIT}" render --technique ${technique} --scene "${room}" --object "${WORK}/tetra.obj" --object-position -2,1.2,1
                 --object-size 0.4 --size 48 --face-size 32 --out "${WORK}/room-${technique}.png")
endforeach()
expect_success("final gathering in room-a.gltf against the Monte Carlo reference" "rel_rmse"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${room}" --object-position 0.5,1.3,1 --object-size 0.4 --size 48
               --face-size 32 --reference monte-carlo --samples 64 --out "${WORK}/room-reference.png")
expect_failure("final gathering in a scene with the object inside the table" "outside the room or inside geometry" "${WORK}/room-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${room}" --object-position -0.5,0.73,-0.6 --size 32 --face-size 32
               --out "${WORK}/room-fail.png")
expect_failure("final gathering in a scene outside its walls" "outside the room or inside geometry" "${WORK}/room-fail*.png"
               "${VPLKIT}" render --technique finalgather-point --scene "${room}" --object-position 0,1,9 --size 32 --face-size 32
               --out "${WORK}/room-fail.png")
expect_failure("final gathering in a scene lit by a sun" "final gathering in scene .*its light is directional" "${WORK}/sun-fail*.png"
               "${VPLKIT}" render --technique envmap --scene indirect-shadow --size 32 --face-size 32 --out "${WORK}/sun-fail.png")
expect_failure("final gathering in a scene file that does not exist" "no-room\\.gltf" "${WORK}/none-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${WORK}/no-room.gltf" --size 32 --out "${WORK}/none-fail.png")

# The sweep draws final gathering in the scene too: one row per configuration, named by the scene.
expect_success("sweep final gathering in room-a.gltf" "wrote .*fg-sweep"
               "${VPLKIT}" sweep --technique finalgather-point --scene "${room}" --object-position 0.5,1.3,1 --object-size 0.4 --size 32
               --face-size 32 --vary cube-resolution=2,4 --out "${WORK}/fg-sweep")
file(GLOB sweep_tables "${WORK}/fg-sweep/*.csv")
set(sweep_text "")
foreach(table ${sweep_tables})
  file(READ "${table}" text)
  string(APPEND sweep_text "${text}")
endforeach()
string(REGEX MATCHALL "room-a[^\n]*finalgather-point" sweep_rows "${sweep_text}")
list(LENGTH sweep_rows sweep_row_count)
if(NOT sweep_row_count EQUAL 2)
  message(SEND_ERROR "FAILED the final gathering sweep in room-a.gltf: ${sweep_row_count} rows naming the scene, not 2:\n${sweep_text}")
  math(EXPR failures "${failures} + 1")
endif()

cli_report()
