# Light Wave ([LW]): every mode renders; bad settings are named.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# Light Wave ([LW]): every mode renders; bad settings are named.
foreach(technique lightwave-direct lightwave-faked lightwave-unshadowed lightwave-accurate lightwave-integrated)
  expect_success("render --technique ${technique}" "technique ${technique}.*shadow maps: [0-9.]+ MB.*wrote .*/${technique}\\.png"
                 "${VPLKIT}" render --technique ${technique} --size 64x36 --shadow-map-scale 1 --out "${WORK}/${technique}.png")
endforeach()
expect_failure("Light Wave ray angle that does not divide 90" "--ray-angle.*must be 1, 2, 3, 5, 6, 9, 10, 15, 18, 30, 45 or 90, got '7'" "${WORK}/lw1.png"
               "${VPLKIT}" render --technique lightwave-accurate --ray-angle 7 --size 32 --out "${WORK}/lw1.png")
expect_failure("Light Wave zero VPLs per ray" "--vpls-per-ray.*must be a whole number in \\[1, 32\\]" "${WORK}/lw2.png"
               "${VPLKIT}" render --technique lightwave-accurate --vpls-per-ray 0 --size 32 --out "${WORK}/lw2.png")
expect_failure("Light Wave more maps than VPLs" "more accurate shadow maps \\(20\\) than VPLs \\(5\\)" "${WORK}/lw3.png"
               "${VPLKIT}" render --technique lightwave-accurate --ray-angle 90 --vpls-per-ray 1 --size 32 --out "${WORK}/lw3.png")
expect_failure("Light Wave negative steps" "--integrated-steps.*must be a whole number in \\[0, 64\\]" "${WORK}/lw4.png"
               "${VPLKIT}" render --technique lightwave-integrated --integrated-steps -1 --size 32 --out "${WORK}/lw4.png")
expect_failure("Light Wave shadow maps beyond 16384: named by the options" "shadow-map-scale 14 with a 1280x720 image \\(size\\) makes shadow maps of 17920 texels per side, more than 16384" "${WORK}/lw5.png"
               "${VPLKIT}" render --technique lightwave-accurate --shadow-map-scale 14 --size 1280x720 --out "${WORK}/lw5.png")
expect_failure("Light Wave shadow map scale out of range" "--shadow-map-scale.*must be a number in \\(0, 16\\]" "${WORK}/lw6.png"
               "${VPLKIT}" render --technique lightwave-accurate --shadow-map-scale 100 --size 320x180 --out "${WORK}/lw6.png")
foreach(bad nan -1 0.2 9 inf)
  expect_failure("--faked-multiplier ${bad}" "--faked-multiplier.*must be a number in \\[0.5, 4\\]" "${WORK}/lw7.png"
                 "${VPLKIT}" render --technique lightwave-faked --faked-multiplier ${bad} --size 32x18 --out "${WORK}/lw7.png")
endforeach()
expect_success("Light Wave writes its indirect shadow factor" "wrote .*/lw8\\.png.*wrote .*/lw8-indirect-shadow\\.png"
               "${VPLKIT}" render --technique lightwave-accurate --size 64x36 --shadow-map-scale 1 --out "${WORK}/lw8.png")
expect_success("Light Wave: the thesis's shadow variant, and no maps" "technique lightwave-accurate"
               "${VPLKIT}" render --technique lightwave-accurate --shadow-variant thesis --shadow-maps 0 --size 64x36 --shadow-map-scale 1 --out "${WORK}/lw9.png")
expect_failure("--shadow-variant that does not exist" "--shadow-variant.*must be importance or thesis" "${WORK}/lw10.png"
               "${VPLKIT}" render --technique lightwave-accurate --shadow-variant fancy --size 64x36 --out "${WORK}/lw10.png")
expect_failure("Light Wave shadow maps beyond memory" "GL_OUT_OF_MEMORY" "${WORK}/lw6.png"
               "${VPLKIT}" render --technique lightwave-accurate --shadow-map-scale 12 --size 1280x720 --out "${WORK}/lw6.png")
expect_success("Light Wave flux energy (the default) says how many VPLs carry light" "6485 VPLs \\(5 degrees, 5 per ray, flux energy: [0-9]+ carry light\\)"
               "${VPLKIT}" render --technique lightwave-unshadowed --size 64x36 --shadow-map-scale 1 --out "${WORK}/lw11.png")
expect_success("Light Wave thesis energy with its max distance" "technique lightwave-accurate, 64x36, 6485 VPLs \\(5 degrees, 5 per ray\\)"
               "${VPLKIT}" render --technique lightwave-accurate --vpl-energy thesis --vpl-max-distance 3 --size 64x36 --shadow-map-scale 1 --out "${WORK}/lw12.png")
expect_failure("--vpl-max-distance without the thesis energy" "vpl-max-distance places the thesis's hemispheres and is read with vpl-energy thesis" "${WORK}/lw13.png"
               "${VPLKIT}" render --technique lightwave-accurate --vpl-max-distance 3 --size 64x36 --out "${WORK}/lw13.png")
expect_failure("--vpl-energy that does not exist" "--vpl-energy.*must be flux or thesis" "${WORK}/lw14.png"
               "${VPLKIT}" render --technique lightwave-accurate --vpl-energy photons --size 64x36 --out "${WORK}/lw14.png")
expect_failure("--vpl-energy is not read by lightwave-direct" "--vpl-energy is read by lightwave-unshadowed, lightwave-accurate and lightwave-integrated \\(the VPL light\\), not by technique lightwave-direct" "${WORK}/lw15.png"
               "${VPLKIT}" render --technique lightwave-direct --vpl-energy thesis --size 64x36 --out "${WORK}/lw15.png")
# A sun: VPLs on parallel rays, a grid of 37 x 37 cells of 5 (docs/errata.md, LW-11).
expect_success("Light Wave with a directional light" "6845 VPLs \\(5 degrees, 5 per ray, flux energy: [0-9]+ carry light\\)"
               "${VPLKIT}" render --technique lightwave-accurate --scene indirect-shadow --size 32 --shadow-map-scale 1 --out "${WORK}/lw16.png")

cli_report()
