# Hostile input: every case exits 1 or 2 with a message naming the input, and writes nothing.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

set(H "${WORK}/hostile")
file(MAKE_DIRECTORY "${H}/deep/er/still")
# 1. OBJ text that two parsers would read differently, or that overflows a float.
file(WRITE "${H}/empty-normal.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n")
file(WRITE "${H}/cr-comment.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n#\rf 1 2 100000\n")
string(ASCII 11 vertical_tab)
file(WRITE "${H}/vertical-tab.obj" "v 0 0 0\nv 1 0 0\nv${vertical_tab}0 1 0\nf 1 2 3\n")
file(WRITE "${H}/float-overflow.obj" "v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
string(REPEAT "1" 100 hundred_digits)
file(WRITE "${H}/hundred-digits.obj" "v ${hundred_digits} 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
file(WRITE "${H}/kd.mtl" "newmtl m\nKd 1e999 0.5 0.5\n")
file(WRITE "${H}/kd-overflow.obj" "mtllib kd.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n")
file(WRITE "${H}/huge.obj" "v 1e10 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
# The material library is /dev/zero, named by a path relative to the OBJ's folder: computed from the
# folder's real path, so that it reaches /dev/zero from a checkout at any depth.
file(REAL_PATH "${H}/deep/er/still" deep_folder)
file(RELATIVE_PATH dev_zero_from_deep_folder "${deep_folder}" "/dev/zero")
file(WRITE "${H}/deep/er/still/dev-zero.obj" "mtllib ${dev_zero_from_deep_folder}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
expect_failure("OBJ: v//vn corner without its normal" "empty-normal\\.obj:4: face corner '1//'" "${H}/out*" "${VPLKIT}" render --scene "${H}/empty-normal.obj" --size 16 --out "${H}/out.png")
expect_failure("OBJ: CR inside a comment (--scene)" "cr-comment\\.obj:5: control character 0x0d" "${H}/out*" "${VPLKIT}" render --scene "${H}/cr-comment.obj" --size 16 --out "${H}/out.png")
expect_failure("OBJ: CR inside a comment (--object)" "cr-comment\\.obj:5: control character 0x0d" "${H}/out*"
               "${VPLKIT}" render --technique finalgather-polygon --object "${H}/cr-comment.obj" --size 16 --face-size 16 --out "${H}/out.png")
expect_failure("OBJ: vertical tab" "vertical-tab\\.obj:3: control character 0x0b" "${H}/out*" "${VPLKIT}" render --scene "${H}/vertical-tab.obj" --size 16 --out "${H}/out.png")
expect_failure("OBJ: 1e39 overflows a float" "float-overflow\\.obj:1: number '1e39' is outside the float range" "${H}/out*"
               "${VPLKIT}" render --scene "${H}/float-overflow.obj" --size 16 --out "${H}/out.png")
expect_failure("OBJ: a 100-digit number" "hundred-digits\\.obj:1: number '1111.*outside the float range" "${H}/out*"
               "${VPLKIT}" render --scene "${H}/hundred-digits.obj" --size 16 --out "${H}/out.png")
expect_failure("MTL: Kd 1e999" "kd-overflow\\.obj:1: mtllib kd\\.mtl: kd\\.mtl:2: number '1e999' is outside the float range" "${H}/out*"
               "${VPLKIT}" reference --scene "${H}/kd-overflow.obj" --size 16 --samples 1 --out "${H}/out.pfm")
expect_failure("reference: coordinates of 1e10" "huge\\.obj:1: number '1e10' is larger than 1000000" "${H}/out*"
               "${VPLKIT}" reference --scene "${H}/huge.obj" --size 16 --samples 1 --out "${H}/out.pfm")
# (The resolved path is echoed cut to 200 bytes, with its length, when the checkout is deep.)
expect_failure("MTL: mtllib names /dev/zero" "dev-zero\\.obj:1: mtllib .*dev/zero: .*dev/zero( \\([0-9]+ bytes\\))?: not a regular file" "${H}/out*"
               "${VPLKIT}" render --scene "${H}/deep/er/still/dev-zero.obj" --size 16 --out "${H}/out.png")
# Kd 0e999 is 0: it loads, and the reference it renders has no NaN (compare refuses non-finite pixels).
file(WRITE "${H}/kd-zero.mtl" "newmtl m\nKd 0e999 0.5 0.5\n")
file(WRITE "${H}/kd-zero.obj" "mtllib kd-zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n")
expect_success("MTL: Kd 0e999 is zero, the reference is finite" "wrote .*/kd-zero\\.pfm"
               "${VPLKIT}" reference --scene "${H}/kd-zero.obj" --size 16 --samples 1 --out "${H}/kd-zero.pfm")
expect_success("the Kd 0e999 reference has finite pixels" "\\| RMSE \\| 0 \\|" "${VPLKIT}" compare "${H}/kd-zero.pfm" "${H}/kd-zero.pfm")
# 3. Arguments and shader lines long enough to overflow a std::regex's stack.
string(REPEAT "1" 100000 long_number)
expect_failure("--object-position of 100000 characters" "--object-position: expected x,y,z, each a finite number.*\\(100004 characters\\)" "${H}/out*"
               "${VPLKIT}" render --technique finalgather-polygon --object-position "${long_number},0,0" --size 16 --out "${H}/out.png")
expect_failure("--size of 100000 characters" "--size: expected N or WxH.*\\(100000 characters\\)" "${H}/out*" "${VPLKIT}" render --size "${long_number}" --out "${H}/out.png")
file(COPY "${SHADERS}/" DESTINATION "${H}/long-line")
string(REPEAT "x" 60000 long_name)
file(APPEND "${H}/long-line/lib/direct_light.glsl" "\n#include \"${long_name}.glsl\"\n")
expect_failure("a shader line of 60000 characters" "lib/direct_light\\.glsl:[0-9]+: the included file name has 60005 characters" "${H}/out*"
               "${VPLKIT}" render --shader-dir "${H}/long-line" --size 16 --out "${H}/out.png")
# 4. compare on NaN and extreme pixels; 5. a PGM named .png; 7. headers that claim gigapixels.
file(COPY "${FUZZ_INPUTS}/pfm/nan-pixel" "${FUZZ_INPUTS}/pfm/inf-pixel" "${FUZZ_INPUTS}/pfm/trailing-bytes" "${FUZZ_INPUTS}/pfm/claims-20000-squared"
          "${FUZZ_INPUTS}/pfm/claims-65536-squared" "${FUZZ_INPUTS}/png/pgm16-named-png" "${FUZZ_INPUTS}/png/claims-65535-squared"
          "${FUZZ_INPUTS}/pfm/extreme-pixels" "${FUZZ_INPUTS}/../corpus/pfm/one-pixel" DESTINATION "${H}/inputs")
foreach(name nan-pixel inf-pixel trailing-bytes claims-20000-squared claims-65536-squared extreme-pixels one-pixel)
  file(RENAME "${H}/inputs/${name}" "${H}/inputs/${name}.pfm")
endforeach()
foreach(name pgm16-named-png claims-65535-squared)
  file(RENAME "${H}/inputs/${name}" "${H}/inputs/${name}.png")
endforeach()
expect_failure("compare: a NaN pixel" "nan-pixel\\.pfm: pixel \\(0, 0\\) \\(from the top left\\) is NaN" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/nan-pixel.pfm" "${H}/inputs/nan-pixel.pfm" --error-image "${H}/out.png")
expect_failure("compare: an infinite pixel" "inf-pixel\\.pfm: pixel \\(0, 0\\) .*is infinite" "${H}/out*" "${VPLKIT}" compare "${H}/inputs/inf-pixel.pfm" "${H}/inputs/inf-pixel.pfm")
expect_failure("compare: bytes after the PFM's pixels" "trailing-bytes\\.pfm: 2 bytes follow the 1x1 pixels" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/trailing-bytes.pfm" "${H}/inputs/trailing-bytes.pfm")
expect_failure("compare: a 34-byte PFM claiming 20000^2" "claims-20000-squared\\.pfm: the image claims 20000x20000 pixels" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/claims-20000-squared.pfm" "${H}/inputs/trailing-bytes.pfm")
expect_failure("compare: a PFM claiming 65536^2" "claims-65536-squared\\.pfm: the image claims 65536x65536 pixels" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/claims-65536-squared.pfm" "${H}/inputs/trailing-bytes.pfm")
expect_failure("compare: a 16-bit PGM named .png" "pgm16-named-png\\.png: not a PNG file \\(no PNG signature\\)" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/pgm16-named-png.png" "${H}/inputs/trailing-bytes.pfm")
expect_failure("compare: a PNG claiming 65535^2" "claims-65535-squared\\.png: the image claims 65535x65535 pixels" "${H}/out*"
               "${VPLKIT}" compare "${H}/inputs/claims-65535-squared.png" "${H}/inputs/trailing-bytes.pfm")
# Pixels of +-3e38 are finite: the metrics and the error image are too.
expect_success("compare: pixels of +-3e38 give finite metrics and an error image" "\\| RMSE \\| [0-9.]+e\\+38 \\|.*\\| PSNR \\(dB\\) \\| -?[0-9.]+ \\|.*wrote .*/extreme-error\\.png"
               "${VPLKIT}" compare "${H}/inputs/extreme-pixels.pfm" "${H}/inputs/one-pixel.pfm" --error-image "${H}/extreme-error.png")

# Issue 26. Depth: a 20,000-node chain loads (no recursion on it); JSON nested 20,000 deep and
# an include chain deeper than 32 are refused by their depth.
set(chain_nodes "")
foreach(i RANGE 1 19999)
  string(APPEND chain_nodes "{\"children\":[${i}]},")
endforeach()
set(triangle_uri "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA")
# A triangle glTF: its nodes (the scene's roots: the first, or the first three when `more` is
# given), the asset's extras, its buffer's URI, and what else the top level has.
function(triangle_gltf path nodes extras uri more)
  set(roots "0")
  if(NOT more STREQUAL "")
    set(roots "0,1,2")
  endif()
  file(WRITE "${path}" "{\"asset\":{\"version\":\"2.0\",\"extras\":${extras}},\"scene\":0,\"scenes\":[{\"nodes\":[${roots}]}],\"nodes\":${nodes},"
       "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
       "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36,"
       "\"uri\":\"${uri}\"}]${more}}")
endfunction()
triangle_gltf("${H}/chain.gltf" "[${chain_nodes}{\"mesh\":0}]" "0" "${triangle_uri}" "")
expect_success("glTF: a chain of 20,000 nodes renders" "wrote .*/chain\\.png" "${VPLKIT}" render --scene "${H}/chain.gltf" --size 16 --out "${H}/chain.png")
string(REPEAT "[" 20000 open_brackets)
string(REPEAT "]" 20000 close_brackets)
triangle_gltf("${H}/deep-extras.gltf" "[{\"mesh\":0}]" "${open_brackets}${close_brackets}" "${triangle_uri}" "")
expect_failure("glTF: extras nested 20,000 arrays deep" "deep-extras\\.gltf: its JSON nests arrays and objects more than 64 deep" "${H}/out*"
               "${VPLKIT}" render --scene "${H}/deep-extras.gltf" --size 16 --out "${H}/out.png")
file(COPY "${SHADERS}/" DESTINATION "${H}/include-chain")
file(APPEND "${H}/include-chain/lib/direct_light.glsl" "\n#include \"lib/chain0.glsl\"\n")
foreach(i RANGE 0 99)
  math(EXPR next "${i} + 1")
  file(WRITE "${H}/include-chain/lib/chain${i}.glsl" "#include \"lib/chain${next}.glsl\"\n")
endforeach()
file(WRITE "${H}/include-chain/lib/chain100.glsl" "// the end\n")
expect_failure("a chain of 100 shader includes" "lib/chain[0-9]+\\.glsl:1: including \"lib/chain[0-9]+\\.glsl\" nests includes more than 32 deep" "${H}/out*"
               "${VPLKIT}" render --shader-dir "${H}/include-chain" --size 16 --out "${H}/out.png")

# Extremes: camera planes whose float inverse projection fails; a light whose reference overflows.
set(lit "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\",\"intensity\":INTENSITY,\"spot\":{\"innerConeAngle\":0.3,\"outerConeAngle\":0.6}}]}},\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":ZNEAR,\"zfar\":ZFAR}}]")
set(lit_nodes "[{\"mesh\":0},{\"camera\":0,\"translation\":[0.3,0.3,2]},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"translation\":[0.3,0.3,0.3]}]")
foreach(planes "0.05;1e7" "1e-6;50")
  list(GET planes 0 znear)
  list(GET planes 1 zfar)
  string(REPLACE "INTENSITY" "10" more "${lit}")
  string(REPLACE "ZNEAR" "${znear}" more "${more}")
  string(REPLACE "ZFAR" "${zfar}" more "${more}")
  triangle_gltf("${H}/camera-${znear}.gltf" "${lit_nodes}" "0" "${triangle_uri}" ",${more}")
  expect_success("reference: a camera with znear ${znear} and zfar ${zfar}" "wrote .*/camera-${znear}\\.pfm"
                 "${VPLKIT}" reference --scene "${H}/camera-${znear}.gltf" --size 32 --samples 2 --out "${H}/camera-${znear}.pfm")
  expect_success("compare reads the reference of znear ${znear}" "\\| RMSE \\| 0 \\|" "${VPLKIT}" compare "${H}/camera-${znear}.pfm" "${H}/camera-${znear}.pfm")
endforeach()
string(REPLACE "INTENSITY" "3.4e38" more "${lit}")
string(REPLACE "ZNEAR" "0.05" more "${more}")
string(REPLACE "ZFAR" "50" more "${more}")
triangle_gltf("${H}/spot-3.4e38.gltf" "${lit_nodes}" "0" "${triangle_uri}" ",${more}")
expect_failure("reference: a spot of intensity 3.4e38" "spot-3\\.4e38\\.gltf: light 0: intensity x color must be in \\[0, 1e\\+20\\]" "${H}/spot*.pfm"
               "${VPLKIT}" reference --scene "${H}/spot-3.4e38.gltf" --size 16 --samples 1 --out "${H}/spot.pfm")

# External files: only the glTF's folder tree, percent-decoded once; an echoed input is cut short.
file(MAKE_DIRECTORY "${H}/elsewhere/outside" "${H}/elsewhere/scene")
file(WRITE "${H}/elsewhere/outside/x.bin" "123456789012345678901234567890123456")
file(WRITE "${H}/elsewhere/scene/in.bin" "123456789012345678901234567890123456")
foreach(case "dotdot;../outside/x.bin" "percent;%2e%2e/outside/x.bin" "percent-upper;%2E%2E/outside/x.bin")
  list(GET case 0 name)
  list(GET case 1 uri)
  triangle_gltf("${H}/elsewhere/scene/${name}.gltf" "[{\"mesh\":0}]" "0" "${uri}" "")
  expect_failure("glTF: buffer ${uri}" "external file '\\.\\./outside/x\\.bin' refused: it has a '\\.\\.' component" "${H}/out*"
                 "${VPLKIT}" render --scene "${H}/elsewhere/scene/${name}.gltf" --size 16 --out "${H}/out.png")
endforeach()
triangle_gltf("${H}/elsewhere/scene/inside.gltf" "[{\"mesh\":0}]" "0" "in%2Ebin" "")
expect_success("glTF: buffer in%2Ebin (in.bin, in its folder)" "wrote .*/inside\\.png" "${VPLKIT}" render --scene "${H}/elsewhere/scene/inside.gltf" --size 16 --out "${H}/inside.png")
string(REPEAT "A" 16777216 sixteen_mebibytes)
triangle_gltf("${H}/data-uri.gltf" "[{\"mesh\":0}]" "0" "data:application/octet-stream;base64,${sixteen_mebibytes}!" "")
set(sixteen_mebibytes "")
execute_process(COMMAND "${VPLKIT}" render --scene "${H}/data-uri.gltf" --size 16 --out "${H}/out.png" RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_VARIABLE out)
string(LENGTH "${err}" err_length)
expect_true("glTF: a broken 16 MiB data URI is not echoed whole (exit ${code}, ${err_length} characters)"
            code EQUAL 1 AND err_length LESS 1200 AND err MATCHES "data-uri[.]gltf: not a readable glTF 2[.]0 file")

foreach(option --technique --scene)
  execute_process(COMMAND "${VPLKIT}" render ${option} "${long_number}" --size 16 --out "${H}/out.png" RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_QUIET)
  string(LENGTH "${err}" err_length)
  expect_true("render ${option} of 100000 characters: cut in the message (exit ${code}, ${err_length} characters)"
              (code EQUAL 1 OR code EQUAL 2) AND err_length LESS 1000 AND err MATCHES "11111[.][.][.] [(]100000 bytes[)]")
endforeach()

# Outputs: a legal 244-character name (its -indirect.pfm has 253); a sibling name too long for
# the file system is refused with the system's reason, nothing written; a size derived from an
# option names it.
string(REPEAT "n" 240 long_name)
expect_success("reference --out with a 244-character name" "wrote .*/${long_name}\\.pfm.*wrote .*/${long_name}-indirect\\.pfm"
               "${VPLKIT}" reference --size 8 --samples 1 --out "${H}/${long_name}.pfm")
expect_failure("render --out whose -visibility-difference.png would have 266 characters" "cannot write .*nnnn-visibility-difference\\.png \\([0-9]+ bytes\\): File name too long"
               "${H}/too-long/*" "${VPLKIT}" render --size 16 --out "${H}/too-long/${long_name}.png")
expect_failure("--face-size 4096" "--face-size: must be a whole number in \\[1, 2730\\] \\(texels\\), got '4096'" "${H}/out*"
               "${VPLKIT}" render --technique finalgather-polygon --face-size 4096 --size 16 --out "${H}/out.png")

# PNG through libspng: an inflate bomb and an index beyond the palette are refused.
file(COPY "${FUZZ_INPUTS}/png/inflate-bomb-1x1" "${FUZZ_INPUTS}/png/palette-index-beyond" DESTINATION "${H}/png")
file(RENAME "${H}/png/inflate-bomb-1x1" "${H}/png/bomb.png")
file(RENAME "${H}/png/palette-index-beyond" "${H}/png/palette.png")
expect_failure("compare: an inflate bomb" "bomb\\.png: not a readable PNG \\(its compressed image data is [0-9]+ bytes, more than a 1x1 image can need" ""
               "${VPLKIT}" compare "${H}/png/bomb.png" "${H}/png/bomb.png")
expect_failure("compare: a palette index beyond the palette" "palette\\.png: not a readable PNG \\(pixel \\(1, 0\\) uses palette entry 5, but the palette has 2\\)" ""
               "${VPLKIT}" compare "${H}/png/palette.png" "${H}/png/palette.png")

cli_report()
