# glTF: a built-in scene exported and read back renders the same image; broken files.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# glTF: a built-in scene exported and read back renders the same image.
expect_success("export-scene writes glTF" "wrote .*cornell-box\\.gltf" "${VPLKIT}" export-scene cornell-box "${WORK}/cornell-box.gltf")
expect_success("render the exported glTF" "scene cornell-box" "${VPLKIT}" render --scene "${WORK}/cornell-box.gltf" --size 32 --rsm-size 64 --out "${WORK}/from-gltf.png")
expect_success("render the built-in scene" "scene cornell-box" "${VPLKIT}" render --scene cornell-box --size 32 --rsm-size 64 --out "${WORK}/built-in.png")
file(SHA256 "${WORK}/from-gltf.png" gltf_hash)
file(SHA256 "${WORK}/built-in.png" built_in_hash)
if(NOT gltf_hash STREQUAL built_in_hash)
  message(SEND_ERROR "FAILED the Cornell box exported to glTF and read back rendered a different image from the built-in one")
  math(EXPR failures "${failures} + 1")
endif()
expect_failure("export-scene: not .gltf" "the output .*\\.gltf" "${WORK}/scene.obj" "${VPLKIT}" export-scene cornell-box "${WORK}/scene.obj")
expect_failure("export-scene: unknown scene" "sponza not in" "${WORK}/sponza.gltf" "${VPLKIT}" export-scene sponza "${WORK}/sponza.gltf")
file(WRITE "${WORK}/broken.gltf" "{\"asset\": ")
expect_failure("render: a broken glTF" "broken\\.gltf: not a readable glTF 2\\.0 file" "${WORK}/broken-render.png"
               "${VPLKIT}" render --scene "${WORK}/broken.gltf" --size 8 --out "${WORK}/broken-render.png")

cli_report()
