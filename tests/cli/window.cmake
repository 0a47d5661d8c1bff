# `vplkit view` in a real window under Xvfb: screenshots equal headless renders, poses, keys and
# mouse.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

expect_failure("view without a display says so" "no GL context: GLFW" ""
               ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY "${VPLKIT}" view --technique lightwave-accurate --frames 1)

# A real window under a virtual X server, when xvfb-run is installed (the setup script installs it).
if(XVFB_RUN)
  # Leak checking is off for this one run: GLFW's glfwTerminate unloads Mesa's DRI driver
  # before LeakSanitizer runs, so the driver's process-lifetime allocations (2 x 56 bytes, seen
  # in the sanitizer build) show without symbols and cannot be suppressed by library name. The
  # frontend code on this path (renderer, programs) is leak-checked by the headless tests.
  expect_success("view opens a window under Xvfb" "closed the window"
                 ${CMAKE_COMMAND} -E env "ASAN_OPTIONS=detect_leaks=0" "${XVFB_RUN}" -a "${VPLKIT}" view --size 64 --rsm-size 64 --frames 3)
  set(view_env ${CMAKE_COMMAND} -E env "ASAN_OPTIONS=detect_leaks=0" "${XVFB_RUN}" -a "${VPLKIT}" view)
  # The window with the panel hidden shows what `vplkit render` writes for the same pose, and the
  # screenshot's indirect PFM is render's -indirect.pfm, for each family.
  foreach(case "rsm-alg6;--rsm-size;64;--camera;0.8,1.2,3.5,0,0.9,0;--light;0.2,1.9,0.1,0,0,0"
               "lightwave-accurate;--camera;1,1.8,3,0,0.3,0;--light;0.5,2.2,0.8,0.3,0,0.4"
               "finalgather-polygon;--face-size;32;--camera;0.5,1.1,3.5,0,0.8,0;--light;0.1,1.9,0,0,0,0;--object-position;0.2,0.7,0"
               "envmap;--scene;${CMAKE_CURRENT_LIST_DIR}/../../bench/scenes/room-a.gltf;--face-size;32;--object-position;0.5,1.3,1;--object-size;0.4")
    list(GET case 0 technique)
    list(SUBLIST case 1 -1 arguments)
    expect_success("render ${technique} from a pose" "wrote" "${VPLKIT}" render --technique ${technique} --size 64 ${arguments} --out "${WORK}/pose-${technique}.png")
    expect_success("view ${technique} from the same pose, panel hidden" "wrote .*view-${technique}\\.png.*pose: --technique ${technique} --camera"
                   ${view_env} --technique ${technique} --size 64 ${arguments} --hide-panel --frames 2 --screenshot "${WORK}/view-${technique}.png")
    compare_within("the hidden-panel window of ${technique} is the headless render" "${WORK}/view-${technique}.png" "${WORK}/pose-${technique}.png" 0.002)
    compare_within("the view's indirect PFM of ${technique} is render's" "${WORK}/view-${technique}-indirect.pfm" "${WORK}/pose-${technique}-indirect.pfm" 1e-6)
  endforeach()
  # The pose the viewer prints renders headless to the same image.
  execute_process(COMMAND ${view_env} --size 64 --rsm-size 64 --hide-panel --frames 2 --screenshot "${WORK}/printed.png" OUTPUT_VARIABLE out RESULT_VARIABLE code)
  string(REGEX MATCH "pose: --technique ([^ ]+) --camera ([^ ]+) --light ([^ \n]+)" printed "${out}")
  if(NOT code EQUAL 0 OR NOT printed)
    message(SEND_ERROR "FAILED view prints its pose: exit ${code}, ${out}")
    math(EXPR failures "${failures} + 1")
  else()
    expect_success("render from the printed pose" "wrote" "${VPLKIT}" render --technique ${CMAKE_MATCH_1} --camera ${CMAKE_MATCH_2} --light ${CMAKE_MATCH_3}
                   --size 64 --rsm-size 64 --out "${WORK}/printed-render.png")
    compare_within("the printed pose renders the window's image" "${WORK}/printed.png" "${WORK}/printed-render.png" 0.002)
  endif()
  # With the panel shown the window is not the render: the panel is there.
  expect_success("view with the panel" "wrote" ${view_env} --technique rsm-alg6 --size 64 --rsm-size 64 --camera 0.8,1.2,3.5,0,0.9,0
                 --light 0.2,1.9,0.1,0,0,0 --frames 3 --screenshot "${WORK}/panel.png")
  execute_process(COMMAND "${VPLKIT}" compare "${WORK}/panel.png" "${WORK}/pose-rsm-alg6.png" OUTPUT_VARIABLE out)
  string(REGEX MATCH "\\| RMSE \\| ([0-9.e+-]+) \\|" found "${out}")
  if(NOT found OR CMAKE_MATCH_1 LESS 0.02)
    message(SEND_ERROR "FAILED the panel shows in the screenshot: RMSE against the render '${CMAKE_MATCH_1}'")
    math(EXPR failures "${failures} + 1")
  endif()
  # The panel over the image covers at most a quarter of it and shows the technique names whole
  # at the default size; docked, it covers none of it and widens the window by its column.
  execute_process(COMMAND ${view_env} --technique lightwave-integrated --size 512 --scene boxes --shadow-map-scale 0.25 --ray-angle 30 --frames 3
                  OUTPUT_VARIABLE out RESULT_VARIABLE code)
  string(REGEX MATCH "panel: [0-9.]+x[0-9.]+ at [0-9.]+,[0-9.]+, covering ([0-9.]+) % of the 512x512 image; technique names (fit|cut)" panel "${out}")
  if(NOT code EQUAL 0 OR NOT panel OR CMAKE_MATCH_1 GREATER 25.0 OR NOT CMAKE_MATCH_2 STREQUAL "fit")
    message(SEND_ERROR "FAILED the floating panel covers at most a quarter of a 512x512 image and shows whole names: exit ${code}, '${panel}'\n${out}")
    math(EXPR failures "${failures} + 1")
  else()
    message(STATUS "ok the floating panel: ${panel}")
  endif()
  expect_success("view --dock-panel puts the panel beside the image" "covering 0\\.0 % of the 64x64 image; technique names fit"
                 ${view_env} --technique rsm-alg6 --size 64 --rsm-size 64 --dock-panel --frames 3 --screenshot "${WORK}/docked.png")
  file(READ "${WORK}/docked.png" header OFFSET 16 LIMIT 8 HEX)
  expect_true("the docked window is the image and the panel's column wide (64 + 340 = 0x194 by 64 = 0x40)" header STREQUAL "0000019400000040")
  # The real input path: a left drag orbits the camera (the RSM stays), Tab then D moves the light
  # (the RSM is redrawn), P saves the screenshot, Esc closes. xdotool drives the X server.
  find_program(XDOTOOL xdotool)
  if(XDOTOOL)
    # Every wait is bounded, so that a key the viewer misses fails the check instead of hanging.
    file(WRITE "${WORK}/input.sh" "set -e
timeout 120 \"$1\" view --size 64 --rsm-size 64 --hide-panel --screenshot \"$2\" > \"$3\" 2>&1 &
pid=$!
w=$(timeout 60 xdotool search --sync --onlyvisible --name 'vplkit view')
sleep 0.5
xdotool mousemove --window \"$w\" 20 30; sleep 0.2
xdotool mousedown 1; sleep 0.2; xdotool mousemove --window \"$w\" 50 30; sleep 0.2; xdotool mouseup 1; sleep 0.2
xdotool key Tab; sleep 0.2
xdotool keydown d; sleep 0.4; xdotool keyup d; sleep 0.2
xdotool key p; sleep 0.5
xdotool key Escape
wait $pid || true
cat \"$3\"
")
    expect_success("mouse and keys move the camera and the light, P saves, Esc closes"
                   "wrote .*keys\\.png.*wrote .*keys-indirect\\.pfm.*closed the window after [0-9]+ frames of rsm-alg6 \\(drawn: RSM ([2-9]|[1-9][0-9]+), G-buffer to post filter [0-9]+\\).*pose: --technique rsm-alg6 --camera -0\\.[0-9]+,1,3\\.[0-9]+,0,1,0 --light 0\\.[0-9]*[1-9][0-9]*,1\\.91999996,0,"
                   ${CMAKE_COMMAND} -E env "ASAN_OPTIONS=detect_leaks=0" "${XVFB_RUN}" -a sh "${WORK}/input.sh" "${VPLKIT}" "${WORK}/keys.png" "${WORK}/keys.log")
  else()
    message(STATUS "skipped the input test: xdotool is not installed")
  endif()
  # A scene without lights: the window shows its image (black), the pose text says --lights none,
  # and the screenshot is written.
  execute_process(COMMAND ${view_env} --technique rsm-alg6 --size 32 --rsm-size 32 --lights none --frames 2 --screenshot "${WORK}/dark.png"
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR NOT "${out}" MATCHES "pose: --technique rsm-alg6 --camera [^ ]+ --lights none\n" OR NOT EXISTS "${WORK}/dark.png")
    message(SEND_ERROR "FAILED view without lights: exit ${code}\n  stdout: ${out}\n  stderr: ${err}")
    math(EXPR failures "${failures} + 1")
  else()
    message(STATUS "ok view without lights: ${out}")
  endif()
  expect_failure("view --screenshot must be a PNG" "--screenshot.*\\.png" "${WORK}/shot.jpg" "${VPLKIT}" view --frames 1 --screenshot "${WORK}/shot.jpg")
  expect_failure("view scopes options like render" "--ray-angle is read by" "" "${VPLKIT}" view --technique rsm-alg6 --ray-angle 3 --frames 1)
  expect_success("info in a window under Xvfb" "using +GLFW window" "${XVFB_RUN}" -a "${VPLKIT}" info --context window)
else()
  message(STATUS "skipped the window tests: xvfb-run is not installed")
endif()

cli_report()
