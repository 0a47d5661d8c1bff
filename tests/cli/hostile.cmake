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
expect_failure("MTL: mtllib names /dev/zero" "dev-zero\\.obj:1: mtllib .*dev/zero: .*dev/zero: not a regular file" "${H}/out*"
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

cli_report()
