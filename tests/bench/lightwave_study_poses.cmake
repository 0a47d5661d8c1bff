# The Light Wave study's cached references are keyed by the pose (issue 40): two poses of one
# scene file get two references, each the one `vplkit reference` computes for that pose byte for
# byte, and a second run reads them back instead of computing them again. (The study once named
# the cache file after the scene file alone, so the second pose silently got the first's.)
#   cmake -DSTUDY=<vplkit_lightwave_study> -DVPLKIT=<vplkit> -DSCENE=<a .gltf> -DWORK=<scratch> -P lightwave_study_poses.cmake
include("${CMAKE_CURRENT_LIST_DIR}/../cli/cli_common.cmake")

set(poses "0.3,1.6,2.8,0,1,0" "-1,1.2,2.5,0.5,1,-1")
list(GET poses 0 first)
list(GET poses 1 second)
set(study_command "${STUDY}" --size 32x18 --samples 4 --seeds 1 --maps 1
                  --scenes "${SCENE}@camera=${first},${SCENE}@camera=${second}" --out "${WORK}/study")
execute_process(COMMAND ${study_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_true("the study runs (exit ${code}: ${err})" code EQUAL 0)
# The full-sample references (reference seed 1): <label>-32x18-<key>-4-r<revision>.pfm.
file(GLOB references "${WORK}/study/references/*-32x18-*-4-r*.pfm")
list(LENGTH references count)
expect_true("two poses of one file: two references (found: ${references})" count EQUAL 2)

if(count EQUAL 2)
  list(GET references 0 reference_0)
  list(GET references 1 reference_1)
  file(SHA256 "${reference_0}" hash_0)
  file(SHA256 "${reference_1}" hash_1)
  expect_true("the two poses' references differ" NOT hash_0 STREQUAL hash_1)
  # Each is right: the Monte Carlo reference of the command line for its pose, the same samples
  # and seed, is the same file byte for byte. The first pose's label is room-a-camera1, the
  # second's room-a-camera1-2.
  set(index 0)
  foreach(pose ${poses})
    execute_process(COMMAND "${VPLKIT}" reference --method monte-carlo --scene "${SCENE}" "--camera=${pose}" --size 32x18 --samples 4
                            --reference-seed 1 --out "${WORK}/pose-${index}.pfm" RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
    expect_true("vplkit reference for pose ${index} (exit ${code}: ${err})" code EQUAL 0)
    file(SHA256 "${WORK}/pose-${index}.pfm" expected)
    if(index EQUAL 0)
      file(GLOB cached "${WORK}/study/references/*-camera1-32x18-*-4-r*.pfm")
    else()
      file(GLOB cached "${WORK}/study/references/*-camera1-2-32x18-*-4-r*.pfm")
    endif()
    set(actual "")
    if(cached)
      file(SHA256 "${cached}" actual)
    endif()
    expect_true("pose ${index}'s cached reference (${cached}) is vplkit reference's for that pose" actual STREQUAL expected)
    math(EXPR index "${index} + 1")
  endforeach()
endif()

# A second run computes no reference: the cache still serves both poses.
execute_process(COMMAND ${study_command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_true("a second run reads both poses' references from the cache (exit ${code}: ${err})" code EQUAL 0 AND NOT err MATCHES "  reference ")

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} check(s) failed")
endif()
