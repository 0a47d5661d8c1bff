# GL contexts: vplkit info, EGL devices and the surfaceless platform, OSMesa, VPLKIT_CONTEXT.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

expect_success("info prints GL and library versions" "vplkit [0-9]+\\.[0-9]+\\.[0-9]+.*GL_VERSION.*GL_RENDERER" "${VPLKIT}" info)
# No GL context: a window without a display.
expect_success("info lists the headless contexts and says which it uses"
               "available headless contexts:.*egl surfaceless:.*osmesa:.*using +EGL .*GL_RENDERER.*timing +" "${VPLKIT}" info)
expect_failure("an EGL device that does not exist" "no EGL device 99: this machine has [0-9]+" ""
               "${VPLKIT}" info --device 99)
expect_failure("VPLKIT_EGL_DEVICE naming no device is an error, not a fallback" "no EGL device 99: this machine has [0-9]+" "${WORK}/device-99.png"
               ${CMAKE_COMMAND} -E env VPLKIT_EGL_DEVICE=99 "${VPLKIT}" render --size 8 --out "${WORK}/device-99.png")
expect_failure("a bad VPLKIT_CONTEXT" "VPLKIT_CONTEXT must be one of auto, egl, egl-surfaceless, osmesa; got 'gles'" "${WORK}/bad-context.png"
               ${CMAKE_COMMAND} -E env VPLKIT_CONTEXT=gles "${VPLKIT}" render --size 8 --out "${WORK}/bad-context.png")
expect_failure("--device with OSMesa" "--device picks an EGL device" "" "${VPLKIT}" info --context osmesa --device 0)
# The surfaceless platform, the fallback when no device platform answers, chosen outright: it
# renders the same image as the device the default picks.
expect_success("info --context egl-surfaceless" "using +EGL surfaceless.*GL_RENDERER" "${VPLKIT}" info --context egl-surfaceless)
expect_success("render on the surfaceless platform" "technique rsm-alg6"
               "${VPLKIT}" render --context egl-surfaceless --size 16 --rsm-size 32 --out "${WORK}/surfaceless.png")
expect_success("render on the default EGL context" "technique rsm-alg6" "${VPLKIT}" render --size 16 --rsm-size 32 --out "${WORK}/default-egl.png")
file(SHA256 "${WORK}/surfaceless.png" surfaceless_hash)
file(SHA256 "${WORK}/default-egl.png" default_hash)
if(NOT surfaceless_hash STREQUAL default_hash)
  message(SEND_ERROR "FAILED the surfaceless platform rendered a different image from the default EGL context")
  math(EXPR failures "${failures} + 1")
endif()
expect_failure("--device with egl-surfaceless" "--device picks an EGL device; egl-surfaceless has none" "${WORK}/surfaceless-device.png"
               "${VPLKIT}" render --context egl-surfaceless --device 0 --size 8 --out "${WORK}/surfaceless-device.png")
if(WITH_OSMESA)
  expect_success("render with --context osmesa" "technique rsm-alg6" "${VPLKIT}" render --context osmesa --size 16 --rsm-size 32 --out "${WORK}/osmesa.png")
else()
  expect_failure("--context osmesa without OSMesa" "built without OSMesa" "${WORK}/osmesa.png"
                 "${VPLKIT}" render --context osmesa --size 16 --rsm-size 32 --out "${WORK}/osmesa.png")
endif()
expect_failure("no GL context (window without a display)" "no GL context: GLFW" ""
               ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY "${VPLKIT}" info --context window)

# The environment variables that stand for options are checked like them (issue 26): a malformed
# one is a usage error (exit 2) naming the variable, never ignored for another context.
foreach(case "VPLKIT_EGL_DEVICE=junk;VPLKIT_EGL_DEVICE must be an EGL device index in \\[0, 1024\\] like --device .*got 'junk'"
             "VPLKIT_EGL_DEVICE=-1;VPLKIT_EGL_DEVICE must be an EGL device index"
             "VPLKIT_CONTEXT=junk;VPLKIT_CONTEXT must be one of auto, egl, egl-surfaceless, osmesa; got 'junk'"
             "VPLKIT_THREADS=junk;VPLKIT_THREADS must be a whole number in \\[1, 1024\\]; got 'junk'"
             "VPLKIT_PROGRESS_SECONDS=0;VPLKIT_PROGRESS_SECONDS must be a number of seconds in \\[0.1, 86400\\]; got '0'")
  list(GET case 0 variable)
  list(GET case 1 pattern)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${variable} "${VPLKIT}" render --size 8 --out "${WORK}/environment.png"
                  RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_QUIET)
  expect_true("${variable} is refused like its option (exit ${code}: ${err})" code EQUAL 2 AND err MATCHES "${pattern}" AND NOT EXISTS "${WORK}/environment.png")
endforeach()
expect_failure("VPLKIT_EGL_DEVICE=99 is a device asked for: no fallback" "no EGL device 99: this machine has [0-9]+ \\(vplkit info lists them\\); VPLKIT_EGL_DEVICE asked for it" "${WORK}/environment.png"
               ${CMAKE_COMMAND} -E env VPLKIT_EGL_DEVICE=99 "${VPLKIT}" render --size 8 --out "${WORK}/environment.png")
expect_failure("VPLKIT_SHADER_DIR that is not a folder" "shader directory not found: ${WORK}/no-such-folder \\(VPLKIT_SHADER_DIR, which stands for --shader-dir\\)" "${WORK}/environment.png"
               ${CMAKE_COMMAND} -E env VPLKIT_SHADER_DIR=${WORK}/no-such-folder "${VPLKIT}" render --size 8 --out "${WORK}/environment.png")
expect_failure("--shader-dir that is not a folder" "shader directory not found: ${WORK}/no-such-folder \\(--shader-dir\\)" "${WORK}/environment.png"
               "${VPLKIT}" render --shader-dir "${WORK}/no-such-folder" --size 8 --out "${WORK}/environment.png")
expect_success("VPLKIT_EGL_DEVICE=0 renders on device 0" "technique rsm-alg6"
               ${CMAKE_COMMAND} -E env VPLKIT_EGL_DEVICE=0 "${VPLKIT}" render --size 8 --out "${WORK}/environment.png")

cli_report()
