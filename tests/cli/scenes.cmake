# Users' scenes as authored (issue 25): --light-intensity scales every output linearly,
# --exposure brightens the PNG and leaves the PFMs alone, a closed room given as an OBJ is framed
# from inside with a note that gives the pose, bad exposure values and textures are refused.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# relative_bias_between(<name> <image> <reference> <low> <high>): `vplkit compare`'s relative bias
# ((mean - reference mean) / reference mean) in [low, high].
function(relative_bias_between name candidate reference low high)
  execute_process(COMMAND "${VPLKIT}" compare "${candidate}" "${reference}" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCH "\\| relative bias [^|]*\\| ([0-9.e+-]+) \\|" found "${out}")
  if(code EQUAL 0 AND found AND CMAKE_MATCH_1 GREATER_EQUAL low AND CMAKE_MATCH_1 LESS_EQUAL high)
    message(STATUS "ok ${name}: relative bias ${CMAKE_MATCH_1}")
  else()
    message(SEND_ERROR "FAILED ${name}: relative bias '${CMAKE_MATCH_1}' not in [${low}, ${high}], exit ${code}\n  ${out}${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  endif()
endfunction()

set(small --size 48 --rsm-size 64)
# --light-intensity: doubling it doubles the indirect PFM (relative bias 1 = twice the mean).
# Light Wave with its default flux energy too (the thesis's VPLs, --vpl-energy thesis, Eq. 4.5,
# carry no light intensity).
foreach(technique rsm-alg6 finalgather-point lightwave-accurate)
  expect_success("${technique} at intensity 3" "wrote" "${VPLKIT}" render --technique ${technique} --size 48 --light-intensity 3 --out "${WORK}/${technique}-3.png")
  expect_success("${technique} at intensity 6" "wrote" "${VPLKIT}" render --technique ${technique} --size 48 --light-intensity 6 --out "${WORK}/${technique}-6.png")
  relative_bias_between("${technique}: twice the intensity, twice the indirect light" "${WORK}/${technique}-6-indirect.pfm" "${WORK}/${technique}-3-indirect.pfm" 0.99 1.01)
endforeach()
# --exposure: 1 EV brightens the PNG; the PFM is the same file.
expect_success("exposure 0" "wrote" "${VPLKIT}" render ${small} --out "${WORK}/ev0.png")
expect_success("exposure 1" "wrote" "${VPLKIT}" render ${small} --exposure 1 --out "${WORK}/ev1.png")
relative_bias_between("--exposure 1 makes the PNG brighter" "${WORK}/ev1.png" "${WORK}/ev0.png" 0.05 1.0)
file(SHA256 "${WORK}/ev0-indirect.pfm" ev0_hash)
file(SHA256 "${WORK}/ev1-indirect.pfm" ev1_hash)
expect_true("--exposure leaves the PFM linear" ev0_hash STREQUAL ev1_hash)
expect_success("exposure auto prints its EV" "exposure: auto, [-0-9.e+]+ EV" "${VPLKIT}" render ${small} --exposure auto --out "${WORK}/auto.png")
expect_success("reference --exposure" "wrote" "${VPLKIT}" reference --size 16 --samples 1 --exposure -1 --light-intensity 2 --out "${WORK}/ref.pfm")
expect_failure("exposure not a number" "--exposure.*auto or a number" "${WORK}/bad-ev.png" "${VPLKIT}" render ${small} --exposure bright --out "${WORK}/bad-ev.png")
expect_failure("exposure out of range" "--exposure.*\\[-32, 32\\]" "${WORK}/bad-ev.png" "${VPLKIT}" render ${small} --exposure 40 --out "${WORK}/bad-ev.png")
expect_failure("negative intensity" "--light-intensity" "${WORK}/bad-i.png" "${VPLKIT}" render ${small} --light-intensity -1 --out "${WORK}/bad-i.png")

# A closed room given as an OBJ, no camera, no light: framed from inside, the pose printed.
set(room "v -3 0 -2.5\nv 3 0 -2.5\nv 3 3 -2.5\nv -3 3 -2.5\nv -3 0 2.5\nv 3 0 2.5\nv 3 3 2.5\nv -3 3 2.5\n")
string(APPEND room "vn 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn -1 0 0\nvn 0 -1 0\nvn 0 1 0\n")
string(APPEND room "f 1//1 2//1 3//1 4//1\nf 5//2 8//2 7//2 6//2\nf 1//3 4//3 8//3 5//3\nf 2//4 6//4 7//4 3//4\nf 4//5 3//5 7//5 8//5\nf 1//6 5//6 6//6 2//6\n")
file(WRITE "${WORK}/room.obj" "${room}")
expect_success("a closed room is framed from inside" "framed as a closed room.*--camera [-0-9.e,]+ --light [-0-9.e,]+"
               "${VPLKIT}" render --scene "${WORK}/room.obj" ${small} --out "${WORK}/room.png")
# A texture that is not an image, and one that is missing: named with the file.
file(WRITE "${WORK}/not-an-image.png" "GIF89a, not a PNG")
file(WRITE "${WORK}/textured.mtl" "newmtl m\nKd 1 1 1\nmap_Kd not-an-image.png\n")
file(WRITE "${WORK}/textured.obj" "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 3/3 2/2\n")
expect_failure("a texture that is not an image" "not-an-image\\.png.*not a PNG or JPEG" "${WORK}/textured.png"
               "${VPLKIT}" render --scene "${WORK}/textured.obj" ${small} --out "${WORK}/textured.png")
file(WRITE "${WORK}/textured.mtl" "newmtl m\nKd 1 1 1\nmap_Kd missing.jpg\n")
expect_failure("a missing texture" "missing\\.jpg" "${WORK}/textured.png" "${VPLKIT}" render --scene "${WORK}/textured.obj" ${small} --out "${WORK}/textured.png")

# BoxTextured from Debian's assimp test models: its texture read, nothing dropped without a note.
set(box "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf")
if(EXISTS "${box}")
  expect_success("BoxTextured renders with its texture" "framed as an object.*scene BoxTextured" "${VPLKIT}" render --scene "${box}" ${small} --out "${WORK}/box.png")
endif()

# Emissive materials (issue 38 item 4). Khronos' ClearCoatTest (in Debian's assimp test models)
# labels its spheres with an emissive texture: it renders, the note says emission is drawn and
# lights nothing, and the frame has an emission pass. A negative emissiveStrength is refused
# naming the file and the material, exit 1, nothing written.
set(clear_coat "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf")
if(EXISTS "${clear_coat}")
  expect_success("ClearCoatTest's emissive labels are drawn" "emissive materials are drawn as seen, but they do not light the scene"
                 "${VPLKIT}" render --scene "${clear_coat}" ${small} --stats "${WORK}/clear-coat.json" --out "${WORK}/clear-coat.png")
  file(READ "${WORK}/clear-coat.json" clear_coat_stats)
  expect_true("ClearCoatTest's frame has an emission pass" "${clear_coat_stats}" MATCHES "\"emission\"")
endif()
file(WRITE "${WORK}/dark-lamp.gltf" "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 0}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"material\": 0}]}], \"materials\": [{\"name\": \"lamp\", \"emissiveFactor\": [1, 1, 1], \"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": -1}}}], \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"min\": [0, 0, 0], \"max\": [1, 1, 0]}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}], \"buffers\": [{\"byteLength\": 36, \"uri\": \"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}]}")
expect_failure("a negative emissiveStrength" "dark-lamp\\.gltf: material 0 'lamp': KHR_materials_emissive_strength's emissiveStrength must be a finite number >= 0, not -1"
               "${WORK}/dark-lamp*.p*" "${VPLKIT}" render --scene "${WORK}/dark-lamp.gltf" ${small} --out "${WORK}/dark-lamp.png")

# --lights (issue 38): bad texts and indices the scene does not have are usage errors, exit code 2
# exactly, the option and the reason named, nothing written.
function(expect_usage_error name pattern must_not_exist)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  file(GLOB left "${must_not_exist}")
  if(NOT code EQUAL 2 OR NOT "${err}" MATCHES "${pattern}" OR left)
    message(SEND_ERROR "FAILED ${name}: exit ${code} (expected 2), stderr must match '${pattern}', left: '${left}'\n  command: ${ARGN}\n  stdout: ${out}\n  stderr: ${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}: exit 2, message: ${err}")
  endif()
endfunction()
expect_usage_error("--lights: a light chosen twice" "--lights.*light 1 is chosen twice, got '1,1'" "${WORK}/bad-l*"
                   "${VPLKIT}" render ${small} --lights 1,1 --out "${WORK}/bad-l.png")
expect_usage_error("--lights: not indices" "--lights.*expected all, none or light indices separated by commas.*'0,,1'" "${WORK}/bad-l*"
                   "${VPLKIT}" render ${small} --lights 0,,1 --out "${WORK}/bad-l.png")
expect_usage_error("--lights: the Cornell box has no light 3" "--lights: the scene has no light 3 \\(it has 1, 0 to 0\\)" "${WORK}/bad-l*"
                   "${VPLKIT}" render ${small} --lights 3 --out "${WORK}/bad-l.png")
expect_usage_error("--light without a light" "--light: the scene has no light to place" "${WORK}/bad-l*"
                   "${VPLKIT}" render ${small} --lights none --light 0,1,0,0,0,0 --out "${WORK}/bad-l.png")
# A glTF with 9 point lights in front of a triangle: refused naming --lights, accepted with two chosen.
set(nine_lights "")
set(nine_nodes "{\"mesh\":0}")
set(nine_scene "0")
foreach(k RANGE 8)
  if(k GREATER 0)
    string(APPEND nine_lights ",")
  endif()
  string(APPEND nine_lights "{\"type\":\"point\",\"intensity\":${k}.5}")
  math(EXPR node "${k} + 1")
  string(APPEND nine_nodes ",{\"extensions\":{\"KHR_lights_punctual\":{\"light\":${k}}},\"translation\":[0.${k},0.3,1]}")
  string(APPEND nine_scene ",${node}")
endforeach()
file(WRITE "${WORK}/nine.gltf" "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[${nine_scene}]}],\"nodes\":[${nine_nodes}],"
     "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
     "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36,"
     "\"uri\":\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],\"extensionsUsed\":[\"KHR_lights_punctual\"],"
     "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[${nine_lights}]}}}")
expect_failure("9 lights: refused naming --lights" "9 lights, at most 8 are rendered \\(choose some with --lights\\)" "${WORK}/nine*.pfm"
               "${VPLKIT}" reference --scene "${WORK}/nine.gltf" --size 8 --samples 1 --out "${WORK}/nine.pfm")
expect_usage_error("9 lights: no light 9" "--lights: the scene has no light 9 \\(it has 9, 0 to 8\\)" "${WORK}/nine*.pfm"
                   "${VPLKIT}" reference --scene "${WORK}/nine.gltf" --lights 0,9 --size 8 --samples 1 --out "${WORK}/nine.pfm")
expect_success("9 lights: --lights 0,2 renders" "wrote .*nine\\.pfm"
               "${VPLKIT}" reference --scene "${WORK}/nine.gltf" --lights 0,2 --size 8 --samples 1 --out "${WORK}/nine.pfm")

cli_report()
