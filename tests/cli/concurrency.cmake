# Two runs writing the same output set at once (issue 26): each set is installed under a lock on
# its folder, so the folder always holds one run's whole set, never a mix (before: 3 mixed sets
# in 40 tries), and no temporary or lock file is left behind. 40 tries: the slow tier.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# The two sets on their own: the Cornell box and the occluder scene, every file different.
foreach(scene cornell-box occluder)
  expect_success("render ${scene} alone" "wrote" "${VPLKIT}" render --scene ${scene} --size 24 --rsm-size 32 --out "${WORK}/${scene}/x.png")
  file(GLOB files RELATIVE "${WORK}/${scene}" "${WORK}/${scene}/*")
  list(SORT files)
  set(hash_${scene} "")
  foreach(name ${files})
    file(SHA256 "${WORK}/${scene}/${name}" hash)
    string(APPEND hash_${scene} "${name}:${hash};")
  endforeach()
endforeach()
set(mixed 0)
set(left_behind "")
foreach(try RANGE 1 40)
  # The two renders at the same time, each with its exit code.
  execute_process(COMMAND sh -c "\"$0\" render --scene cornell-box --size 24 --rsm-size 32 --out \"$1\" >/dev/null 2>&1 & first=$!
                                 \"$0\" render --scene occluder --size 24 --rsm-size 32 --out \"$1\" >/dev/null 2>&1
                                 second=$?; wait $first; echo \"$? $second\""
                          "${VPLKIT}" "${WORK}/both/x.png"
                  OUTPUT_VARIABLE codes ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
  file(GLOB files RELATIVE "${WORK}/both" "${WORK}/both/*" "${WORK}/both/.*")  # temporaries and the lock are hidden
  list(REMOVE_DUPLICATES files)
  list(SORT files)
  set(hash_both "")
  foreach(name ${files})
    file(SHA256 "${WORK}/both/${name}" hash)
    string(APPEND hash_both "${name}:${hash};")
  endforeach()
  if(NOT codes STREQUAL "0 0")
    message(SEND_ERROR "FAILED try ${try}: exit codes ${codes}: ${err}")
    math(EXPR failures "${failures} + 1")
  elseif(NOT hash_both STREQUAL hash_cornell-box AND NOT hash_both STREQUAL hash_occluder)
    math(EXPR mixed "${mixed} + 1")
    string(APPEND left_behind " try ${try}: ${files}")
  endif()
endforeach()
expect_true("40 tries of two concurrent renders to one --out: ${mixed} mixed sets${left_behind}" mixed EQUAL 0)

cli_report()
