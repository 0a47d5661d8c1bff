# Long work announced and bounded (issue 26): the Monte Carlo reference prints its cost in rays and
# an estimate before it starts, plain progress lines every few seconds when stderr is a pipe (as
# here), and --max-seconds stops a run that outlasts it, writing nothing; a pose sequence reports
# its frames and stops after the frame in which --max-seconds ran out. The lines come every
# $VPLKIT_PROGRESS_SECONDS (5 s where it is not set; 0.5 s here, so that runs of a few seconds
# show several lines; tests/frontend/core/test_progress.cpp checks the variable's parsing), and
# every run has one thread (VPLKIT_THREADS=1), so that its length does not shrink with the
# machine's cores: about 12 s in all, the slow tier.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# About 6 s on one core (6.6e7 rays; more on a loaded machine): at least two progress lines at
# 0.5 s intervals, also on a core five times as fast.
set(one_thread_fast_lines ${CMAKE_COMMAND} -E env VPLKIT_PROGRESS_SECONDS=0.5 VPLKIT_THREADS=1)
execute_process(COMMAND ${one_thread_fast_lines} "${VPLKIT}" reference --size 64 --samples 8000 --out "${WORK}/long.pfm" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "one-bounce Monte Carlo reference: [0-9]+% \\([0-9]+ of 4096 pixels\\), [0-9.]+ (s|min) elapsed, about [^\n]+ left\n" lines "${err}")
list(LENGTH lines line_count)
expect_true("reference on a pipe: the cost first, ${line_count} progress lines, done (exit ${code})"
            code EQUAL 0 AND line_count GREATER_EQUAL 2 AND err MATCHES "^vplkit reference: 4096 pixels x .*: at most 6[.]55e[+]07 rays, estimated [0-9.]+ (s|min) on [0-9]+ threads?\n"
            AND err MATCHES "one-bounce Monte Carlo reference: done in [0-9.]+ (s|min)\n" AND EXISTS "${WORK}/long.pfm")
# The same run with 2 s to do it: refused at once when the estimate says so, else stopped at 2 s.
execute_process(COMMAND ${one_thread_fast_lines} "${VPLKIT}" reference --size 64 --samples 8000 --max-seconds 2 --out "${WORK}/bounded.pfm" RESULT_VARIABLE code ERROR_VARIABLE err)
expect_true("reference --max-seconds 2 of a 6 s run: refused or stopped, nothing written (exit ${code}: ${err})"
            code EQUAL 1 AND (err MATCHES "exceeds --max-seconds 2. nothing is written" OR err MATCHES "stopped after [0-9]+ s at [0-9]+% [(]--max-seconds 2[)]. nothing is written")
            AND NOT EXISTS "${WORK}/bounded.pfm" AND NOT EXISTS "${WORK}/bounded.png")

# A long pose sequence (issue 36): progress lines on a pipe, with the frames done and the time left,
# and --max-seconds 4 stops it after the frame in which the 4 s ran out (exit 3).
string(REPEAT "--light 0.2,1.9,0.1,0,0,0\n--camera 0.5,1,3.5,0,1,0\n" 500 thousand_poses)
file(WRITE "${WORK}/poses.txt" "")
foreach(block RANGE 1 100)
  file(APPEND "${WORK}/poses.txt" "${thousand_poses}")
endforeach()
# 100,000 frames (the most a pose file may have): minutes at any speed, so 4 s always stops it.
execute_process(COMMAND ${one_thread_fast_lines} "${VPLKIT}" render --poses "${WORK}/poses.txt" --size 16 --rsm-size 64 --max-seconds 4 --out "${WORK}/seq.png"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "render --poses: [0-9]+% \\([0-9]+ of 100000 frames\\), [0-9.]+ (s|min) elapsed, about [^\n]+ left\n" lines "${err}")
list(LENGTH lines line_count)
expect_true("render --poses on a pipe: ${line_count} progress lines, then stopped by --max-seconds 4 (exit ${code}): ${err}"
            code EQUAL 3 AND line_count GREATER_EQUAL 2 AND err MATCHES "stopped by --max-seconds 4 after [0-9]+ s: wrote frames 1 to [0-9]+ of 100000"
            AND EXISTS "${WORK}/seq-000001.png" AND EXISTS "${WORK}/seq-000001-indirect.pfm")

cli_report()
