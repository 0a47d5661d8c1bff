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
set(room "${CMAKE_CURRENT_LIST_DIR}/../../bench/scenes/room-a.gltf")
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
# Every light of the scene: fg-studio-two.gltf's spot and bulb, each with its passes in the table;
# --lights picks them; --lights none is drawn unlit. An open scene (indirect-shadow, lit by a sun)
# is refused by the cube-map check, not for its light.
set(studio_two "${CMAKE_CURRENT_LIST_DIR}/../../bench/scenes/fg-studio-two.gltf")
expect_success("final gathering with two lights (a spot and a point light): the time per light"
               "light depth light 1 .*cube map light 1 .*direct light light 1 .*wrote .*/two-lights\\.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio_two}" --object-position 0,1.3,0.6 --object-size 0.4
               --size 32 --face-size 32 --out "${WORK}/two-lights.png")
expect_success("final gathering with the scene's point light alone (--lights 1)" "object sphere .*wrote .*/bulb\\.png"
               "${VPLKIT}" render --technique finalgather-point --scene "${studio_two}" --lights 1 --object-position 0,1.3,0.6
               --object-size 0.4 --size 32 --face-size 32 --out "${WORK}/bulb.png")
expect_success("final gathering with no light (--lights none)" "object sphere .*wrote .*/unlit\\.png"
               "${VPLKIT}" render --technique envmap --scene "${studio_two}" --lights none --object-position 0,1.3,0.6
               --object-size 0.4 --size 32 --face-size 32 --out "${WORK}/unlit.png")
expect_failure("final gathering in an open scene lit by a sun" "outside the room or inside geometry" "${WORK}/sun-fail*.png"
               "${VPLKIT}" render --technique envmap --scene indirect-shadow --size 32 --face-size 32 --out "${WORK}/sun-fail.png")
expect_failure("final gathering: --lights names a light the scene lacks" "--lights: the scene has no light 2 \\(it has 2, 0 to 1\\)"
               "${WORK}/lights-fail*.png"
               "${VPLKIT}" render --technique envmap --scene "${studio_two}" --lights 2 --size 32 --face-size 32 --out "${WORK}/lights-fail.png")
expect_failure("final gathering in a scene file that does not exist" "no-room\\.gltf" "${WORK}/none-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${WORK}/no-room.gltf" --size 32 --out "${WORK}/none-fail.png")

# The object as a node of the scene (--object-node) and placed by --object-at: fg-studio.gltf's
# vase (a 0.16 x 0.26 x 0.16 box, 12 triangles) stands on the desk; moved to the middle of the
# room, the bottom centre of its box at 0,1.1,0.6, its centre is 0.13 higher.
set(studio "${CMAKE_CURRENT_LIST_DIR}/../../bench/scenes/fg-studio.gltf")
expect_success("final gathering with a node of the scene as the object, moved by --object-at"
               "object vase \\(12 triangles\\) at \\(0, 1.23, 0.6\\).*wrote .*/studio-vase\\.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-node vase --object-at 0,1.1,0.6 --size 48
               --face-size 32 --out "${WORK}/studio-vase.png")
expect_success("--object-at scales: the vase twice as large" "object vase \\(12 triangles\\) at \\(0, 1.36, 0.6\\)"
               "${VPLKIT}" render --technique envmap --scene "${studio}" --object-node vase --object-at 0,1.1,0.6,2 --size 32
               --face-size 32 --out "${WORK}/studio-vase2.png")
expect_success("--object FILE placed by --object-at (its own units, scaled)" "object tetra .*at \\(0, 1.25, 0\\)"
               "${VPLKIT}" render --technique finalgather-point --scene "${studio}" --object "${WORK}/tetra.obj" --object-at 0,1,0,0.5 --size 32
               --face-size 32 --out "${WORK}/studio-tetra.png")
expect_failure("a node resting on the desk touches it: the cube-map check" "reference point \\(-1.3.*within the object's radius" "${WORK}/studio-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-node vase --size 32 --face-size 32
               --out "${WORK}/studio-fail.png")
expect_failure("an unknown node is refused with the scene's node names"
               "no node named 'urn' \\(--object-node\\); its named nodes: 'floor', 'ceiling', 'back wall'.*'vase', 'camera', 'spot'"
               "${WORK}/studio-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-node urn --size 32 --out "${WORK}/studio-fail.png")
expect_failure("--object-node without --scene" "--object-node 'vase' names a node of the scene: give the glTF scene with --scene"
               "${WORK}/studio-fail*.png" "${VPLKIT}" render --technique finalgather-polygon --object-node vase --size 32 --out "${WORK}/studio-fail.png")
expect_failure("--object-node and --object" "give it or --object, not both" "${WORK}/studio-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-node vase --object "${WORK}/tetra.obj" --size 32
               --out "${WORK}/studio-fail.png")
expect_failure("--object-node with --object-position" "the node --object-node names stays where the scene has it, or give --object-at"
               "${WORK}/studio-fail*.png" "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-node vase
               --object-position 0,1,0 --size 32 --out "${WORK}/studio-fail.png")
foreach(case "1,2|expected x,y,z or x,y,z,scale, not '1,2'" "0,1,nan|x, y and z must be finite" "0,1,0,0|the scale must be > 0"
             "0,1,0,-2|the scale must be > 0" "0,1,x|expected x,y,z or x,y,z,scale" "0,1,0,1,5|expected x,y,z or x,y,z,scale")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 value)
  list(GET parts 1 message)
  expect_failure("--object-at ${value} is refused" "--object-at.*${message}" "${WORK}/studio-fail*.png"
                 "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-at "${value}" --size 32 --out "${WORK}/studio-fail.png")
endforeach()
expect_failure("--object-at outside the scene's bounds" "--object-at 0,1,40 puts the object's box .* outside the scene's bounds"
               "${WORK}/studio-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-at 0,1,40 --size 32 --out "${WORK}/studio-fail.png")
expect_failure("--object-at and --object-position" "give it or --object-position and --object-size, not both" "${WORK}/studio-fail*.png"
               "${VPLKIT}" render --technique finalgather-polygon --scene "${studio}" --object-at 0,1,0 --object-size 0.3 --size 32
               --out "${WORK}/studio-fail.png")

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
