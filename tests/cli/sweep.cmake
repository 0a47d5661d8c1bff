# `vplkit sweep` and `vplkit render --stats`: usage errors exit 2 and write nothing; a grid on OBJ,
# glTF and built-in scenes writes its rows, the varied settings as columns, the quality against
# the reference, the plots; a rerun resumes; every family sweeps; the specifications in bench/
# plan without an error. Tiny frames: the fast tier.
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")
# A row split at its commas keeps its empty cells (an undefined metric leaves its _sd cell empty),
# so that a column's index is the same in every row.
cmake_policy(SET CMP0007 NEW)

# expect_usage_error(<name> <message regex> <folder that must not appear> <args...>): exit 2,
# the message, and no folder (nothing written).
function(expect_usage_error name pattern folder)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(problem "")
  if(NOT code EQUAL 2)
    set(problem "exit code ${code}, expected 2")
  elseif(NOT "${out}${err}" MATCHES "${pattern}")
    set(problem "output does not match '${pattern}'")
  elseif(EXISTS "${folder}")
    set(problem "wrote ${folder}")
    file(REMOVE_RECURSE "${folder}")
  endif()
  if(problem)
    message(SEND_ERROR "FAILED ${name}: ${problem}\n  command: ${ARGN}\n  stdout: ${out}\n  stderr: ${err}")
    math(EXPR count "${failures} + 1")
    set(failures ${count} PARENT_SCOPE)
  else()
    message(STATUS "ok ${name}: ${err}")
  endif()
endfunction()

# The rows of a sweep.csv as a list of lines, the header first.
function(read_rows csv variable)
  file(STRINGS "${csv}" lines)
  set(${variable} "${lines}" PARENT_SCOPE)
endfunction()

# The index of `column` in a CSV header line (no quoted commas in these headers).
function(column_index header column variable)
  string(REPLACE "," ";" names "${header}")
  list(FIND names "${column}" index)
  set(${variable} ${index} PARENT_SCOPE)
endfunction()

# A small room as OBJ: a floor, two walls, a table-like box.
file(WRITE "${WORK}/room.obj" "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv -2 2 -2\nv 2 2 -2\nv -2 2 2\n"
                              "v -0.5 0.6 -0.5\nv 0.5 0.6 -0.5\nv 0.5 0.6 0.5\nv -0.5 0.6 0.5\n"
                              "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 1 5 7\nf 1 7 4\nf 8 10 9\nf 8 11 10\n")
set(tiny --size 24 --rsm-size 32 --repeat 2 --min-rounds 1)

# --- usage errors: exit 2, nothing written --------------------------------------------------
expect_usage_error("a setting the technique does not read names who reads it"
                   "--vary slots: slots is read by rsm-alg2, rsm-alg3, rsm-alg6 and rsm-alg6-ray \\(the micro linear buffer\\), not by technique rsm-radial" "${WORK}/u1"
                   "${VPLKIT}" sweep --technique rsm-radial --vary slots=4,8 --out "${WORK}/u1")
expect_usage_error("no such setting lists what the technique reads" "--vary radiuss: no setting 'radiuss'; technique rsm-radial reads: size, .*radius, .*paths"
                   "${WORK}/u2" "${VPLKIT}" sweep --technique rsm-radial --vary radiuss=0.1,0.2 --out "${WORK}/u2")
expect_usage_error("a Light Wave setting on an RSM technique" "--vary shadow-maps: shadow-maps is read by lightwave-accurate" "${WORK}/u3"
                   "${VPLKIT}" sweep --technique rsm-alg6 --vary shadow-maps=1,2 --out "${WORK}/u3")
expect_usage_error("a value out of the setting's range" "--vary radius=3: radius must be a number in \\(0, 2\\]" "${WORK}/u4"
                   "${VPLKIT}" sweep --technique rsm-radial --vary radius=0.5,3 --out "${WORK}/u4")
expect_usage_error("--vary without values" "--vary radius: expected NAME=v1,v2" "${WORK}/u5" "${VPLKIT}" sweep --vary radius --out "${WORK}/u5")
expect_usage_error("the brute force measures RSM techniques only" "rsm-brute-force: the brute-force RSM gather is the reference of the RSM techniques" "${WORK}/u6"
                   "${VPLKIT}" sweep --technique lightwave-accurate --vary shadow-maps=1,2 --reference rsm-brute-force --out "${WORK}/u6")
expect_usage_error("--seeds for a technique without a seed" "--seeds 3: technique direct reads no seed" "${WORK}/u7"
                   "${VPLKIT}" sweep --technique direct --vary rsm-size=16,32 --seeds 3 --out "${WORK}/u7")
expect_usage_error("a configuration the family refuses" "configuration cube-resolution=3: M = 3 does not divide the face size 32" "${WORK}/u8"
                   "${VPLKIT}" sweep --technique finalgather-point --face-size 32 --vary cube-resolution=2,3 --out "${WORK}/u8")
expect_usage_error("--out is required" "--out is required" "${WORK}/u10" "${VPLKIT}" sweep --vary radius=0.1,0.2)
expect_usage_error("a technique of another family on the technique axis" "--vary technique=lightwave-direct: not a technique of the rsm family" "${WORK}/u11"
                   "${VPLKIT}" sweep --technique rsm-alg6 --vary technique=rsm-radial,lightwave-direct --out "${WORK}/u11")
expect_usage_error("a setting given and not read by the technique" "--ray-angle: ray-angle is read by" "${WORK}/u12"
                   "${VPLKIT}" sweep --technique rsm-alg6 --ray-angle 10 --vary radius=0.1,0.2 --out "${WORK}/u12")

# --- a grid on an OBJ and a glTF scene against the brute force ------------------------------
expect_success("export a built-in scene as glTF" "wrote" "${VPLKIT}" export-scene occluder "${WORK}/occluder.gltf")
expect_success("sweep radius on OBJ and glTF scenes against the brute force, progress on a pipe"
               "sweep: [0-9]+ % .*left.*wrote .*sweep\\.csv.*wrote .*sweep\\.md"
               "${VPLKIT}" sweep --technique rsm-radial --scene "${WORK}/room.obj" --scene "${WORK}/occluder.gltf" ${tiny} --vary radius=0.125,0.5
               --reference rsm-brute-force --seeds 2 --out "${WORK}/s1")
read_rows("${WORK}/s1/sweep.csv" rows)
list(LENGTH rows count)
expect_true("4 rows: 2 radii x 2 scenes (and the header)" count EQUAL 5)
list(GET rows 0 header)
expect_true("the CSV names the varied setting and the measures" header MATCHES "^scene,technique,radius,frame_ms,.*,machine,.*,rel_rmse,rel_rmse_sd,rel_rmse_seed1,rel_rmse_seed2,rel_rmse_worst,rel_rmse_worst_seed,.*rel_bias,.*pareto,tie,key$")
column_index("${header}" "radius" radius_column)
column_index("${header}" "rel_bias" bias_column)
column_index("${header}" "frame_ms" time_column)
column_index("${header}" "pareto" pareto_column)
# A larger radius reaches more of the RSM's light: the gathered light (and its bias) grows.
foreach(scene room occluder)
  set(biases "")
  foreach(row ${rows})
    if(row MATCHES "^${scene},")
      string(REPLACE "," ";" cells "${row}")
      list(GET cells ${bias_column} bias)
      list(GET cells ${time_column} time)
      list(GET cells ${pareto_column} pareto)
      expect_true("${scene}: rel_bias and frame_ms are numbers, pareto is 0 or 1" bias MATCHES "^-?[0-9]" AND time MATCHES "^[0-9]" AND pareto MATCHES "^[01]$")
      list(APPEND biases ${bias})
    endif()
  endforeach()
  list(GET biases 0 small_radius)
  list(GET biases 1 large_radius)
  expect_true("${scene}: rel_bias rises with the radius (${small_radius} < ${large_radius})" small_radius LESS large_radius)
endforeach()
expect_true("sweep.md and the plots" EXISTS "${WORK}/s1/sweep.md")
file(READ "${WORK}/s1/sweep.md" md)
expect_true("sweep.md names the timing method and the reference" md MATCHES "wall clock|timer queries" AND md MATCHES "brute-force gather")
find_program(GNUPLOT gnuplot)
if(GNUPLOT)
  expect_true("a plot per varied setting and the Pareto front" EXISTS "${WORK}/s1/radius.png" AND EXISTS "${WORK}/s1/pareto.png")
endif()

# Resuming: the rows there are kept, only the new configurations run.
file(SHA256 "${WORK}/s1/sweep.csv" before)
expect_success("a rerun resumes and adds nothing" "resuming .*4 row\\(s\\)"
               "${VPLKIT}" sweep --technique rsm-radial --scene "${WORK}/room.obj" --scene "${WORK}/occluder.gltf" ${tiny} --vary radius=0.125,0.5
               --reference rsm-brute-force --seeds 2 --out "${WORK}/s1")
read_rows("${WORK}/s1/sweep.csv" again)
expect_true("the resumed CSV is the same rows" again STREQUAL rows)
expect_success("a rerun with one more radius runs only it" "resuming"
               "${VPLKIT}" sweep --technique rsm-radial --scene "${WORK}/room.obj" --scene "${WORK}/occluder.gltf" ${tiny} --vary radius=0.125,0.5,0.75
               --reference rsm-brute-force --seeds 2 --out "${WORK}/s1")
read_rows("${WORK}/s1/sweep.csv" grown)
list(LENGTH grown count)
expect_true("6 rows after resuming with a third radius" count EQUAL 7)
# Each earlier row kept as it was, measurements and timing included; only its Pareto flag and tie
# may change, the front now holding the third radius too (its time varies with the machine's load).
column_index("${header}" "tie" tie_column)
function(without_pareto row variable)
  string(REPLACE "," ";" cells "${row}")
  list(REMOVE_AT cells ${pareto_column} ${tie_column})
  set(${variable} "${cells}" PARENT_SCOPE)
endfunction()
set(grown_measures "")
foreach(row ${grown})
  without_pareto("${row}" measures)
  list(APPEND grown_measures "${measures}")
endforeach()
list(SUBLIST rows 1 -1 earlier)
foreach(row ${earlier})
  without_pareto("${row}" measures)
  string(FIND "${grown_measures}" "${measures}" kept)
  expect_true("the earlier row ${row} is kept as it was (but its Pareto flag)" kept GREATER -1)
endforeach()
expect_usage_error("resuming needs the same --vary" "holds a sweep over other settings \\(radius\\)" "${WORK}/s1/paths.png"
                   "${VPLKIT}" sweep --technique rsm-radial ${tiny} --vary paths=5,10 --out "${WORK}/s1")

# --- a black reference: the light points away, so the brute force is 0 at every receiver. The
# relative numbers are "undefined" with the reason, not 0, and no row is on the Pareto front
# (with 0s, the fastest row was marked best).
expect_success("a sweep against a black reference" "rel_rmse undefined.*wrote .*sweep\\.csv"
               "${VPLKIT}" sweep --technique rsm-radial --scene cornell-box --light 0,100,0,0,200,0 ${tiny} --vary radius=0.125,0.5
               --reference rsm-brute-force --out "${WORK}/black")
read_rows("${WORK}/black/sweep.csv" rows)
list(GET rows 0 header)
column_index("${header}" "rel_rmse" rmse_column)
column_index("${header}" "pareto" pareto_column)
list(LENGTH rows count)
expect_true("black: 2 rows, a column saying why" count EQUAL 3 AND header MATCHES ",undefined,")
list(SUBLIST rows 1 -1 data_rows)
foreach(row ${data_rows})
  string(REPLACE "," ";" cells "${row}")
  list(GET cells ${rmse_column} rmse)
  list(GET cells ${pareto_column} pareto)
  expect_true("black: rel_rmse is undefined (${rmse}), the row is not on the Pareto front (${pareto})" rmse STREQUAL "undefined" AND NOT pareto STREQUAL "1")
  expect_true("black: the row says why" row MATCHES "rel_rmse: the reference's mean is 0 .black.")
endforeach()
file(READ "${WORK}/black/sweep.md" md)
expect_true("black: sweep.md shows undefined and the reason" md MATCHES "[|] undefined [|]" AND md MATCHES "Undefined numbers.*_rmse: the reference.s mean is 0")
expect_success("render --stats against a black reference" "\\| rel_rmse \\| undefined: the reference's mean is 0 \\(black\\)"
               "${VPLKIT}" render --technique rsm-alg6 --scene occluder --light 0,100,0,0,200,0 --size 24 --rsm-size 32 --reference rsm-brute-force
               --stats "${WORK}/black-stats.json" --out "${WORK}/black-stats.png")
file(READ "${WORK}/black-stats.json" json)
string(JSON rmse_type TYPE "${json}" quality rel_rmse)
string(JSON why GET "${json}" quality undefined rel_rmse)
expect_true("the JSON's rel_rmse is null, the reason under undefined" rmse_type STREQUAL "NULL" AND why MATCHES "^the reference's mean is 0 .black.")

# --- every family: Light Wave's shadow maps against the base configuration, final gathering's
# techniques and M against Monte Carlo, a zipped axis and the technique axis ---------------------
expect_success("a Light Wave sweep of shadow-maps" "wrote .*sweep\\.csv"
               "${VPLKIT}" sweep --technique lightwave-accurate --scene "${WORK}/room.obj" --size 32x18 --shadow-map-scale 1 --vary shadow-maps=0,5
               --reference base --repeat 2 --min-rounds 1 --out "${WORK}/lw")
read_rows("${WORK}/lw/sweep.csv" rows)
list(LENGTH rows count)
list(GET rows 0 header)
expect_true("Light Wave: 2 rows, the shadow-maps column, Alg. 1 similarity" count EQUAL 3 AND header MATCHES "shadow-maps" AND header MATCHES "similarity")
expect_success("a final-gathering sweep of techniques x M against Monte Carlo" "wrote .*sweep\\.csv"
               "${VPLKIT}" sweep --technique finalgather-point --size 24 --face-size 16 --vary technique=finalgather-point,finalgather-polygon
               --vary cube-resolution=4,2 --reference monte-carlo --samples 8 --repeat 2 --min-rounds 1 --out "${WORK}/fg")
read_rows("${WORK}/fg/sweep.csv" rows)
list(LENGTH rows count)
list(GET rows 1 row)
expect_true("final gathering: 4 rows on the sphere with rel_rmse" count EQUAL 5 AND row MATCHES "^sphere,finalgather-(point|polygon),[42]," AND rows MATCHES "rel_rmse")
expect_success("a zipped axis and the technique axis on a built-in scene" "wrote .*sweep\\.csv"
               "${VPLKIT}" sweep --technique rsm-radial --scene cornell-box ${tiny} --vary technique=rsm-radial,rsm-alg6 --vary paths:samples-per-path=5:4,10:8
               --vary slots=4,8 --out "${WORK}/zip")
read_rows("${WORK}/zip/sweep.csv" rows)
list(LENGTH rows count)
# rsm-radial reads no slots: its 2 configurations are not repeated per slot count; rsm-alg6 has 2 x 2.
expect_true("6 configurations: the radial ones once, Alg. 6 per slot count" count EQUAL 7)
expect_true("the zipped settings are two columns" rows MATCHES "^scene,technique,paths,samples-per-path,slots,")

# --- specifications: bench/*.sweep plan; a section with an error stops every section -----------
file(GLOB specs "${CMAKE_CURRENT_LIST_DIR}/../../bench/*.sweep")
foreach(spec ${specs})
  get_filename_component(spec_name "${spec}" NAME)
  expect_success("${spec_name} plans" "configuration" "${VPLKIT}" sweep --spec "${spec}" --plan --out "${WORK}/plan")
endforeach()
expect_true("the plan wrote nothing" NOT EXISTS "${WORK}/plan")
file(WRITE "${WORK}/tiny.sweep" "# two sections\n--technique rsm-radial --size 16 --rsm-size 16\n[radius]\n--vary radius=0.25,0.5\n[paths]\n--vary \"paths=4,8\"\n")
expect_success("a specification runs each section into its folder" "sweep \\[radius\\].*sweep \\[paths\\]"
               "${VPLKIT}" sweep --spec "${WORK}/tiny.sweep" --repeat 1 --min-rounds 1 --out "${WORK}/spec")
expect_true("a folder per section" EXISTS "${WORK}/spec/radius/sweep.csv" AND EXISTS "${WORK}/spec/paths/sweep.csv")
file(WRITE "${WORK}/broken.sweep" "--technique rsm-radial\n[good]\n--vary radius=0.25,0.5\n[bad]\n--vary slots=4,8\n")
expect_usage_error("a specification with a bad section writes nothing" "\\[bad\\] --vary slots: slots is read by" "${WORK}/broken"
                   "${VPLKIT}" sweep --spec "${WORK}/broken.sweep" --out "${WORK}/broken")

# --- no injection: a scene named with a line end, a gnuplot command, quotes and a backslash, into
# an --out with an apostrophe and a space. gnuplot gets the names as data (and the paths as its
# ARG1 and ARG2), so nothing runs and the plots are drawn; every writer keeps the name as text. ----
file(MAKE_DIRECTORY "${WORK}/hostile")
set(evil "${WORK}/hostile/evil\nsystem \"touch MARKER\"\n#'\\.obj")
file(READ "${WORK}/room.obj" room_obj)
file(WRITE "${evil}" "${room_obj}")
set(hostile_out "${WORK}/hostile/plain")
set(hostile_sweep "${VPLKIT}" sweep --technique rsm-radial --scene "${evil}" ${tiny} --vary radius=0.125,0.5)
execute_process(COMMAND ${hostile_sweep} --out "${hostile_out}" WORKING_DIRECTORY "${WORK}/hostile" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_true("a sweep of a hostile scene name exits 0 (${code}: ${err})" code EQUAL 0)
# The same measured (a Pareto plot too) into an --out with an apostrophe.
execute_process(COMMAND ${hostile_sweep} --reference rsm-brute-force --out "${WORK}/hostile/it's out" WORKING_DIRECTORY "${WORK}/hostile"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_true("the same into an --out with an apostrophe and a space exits 0 (${code}: ${err})" code EQUAL 0)
file(GLOB_RECURSE markers "${WORK}/*MARKER" "${CMAKE_CURRENT_BINARY_DIR}/MARKER")
expect_true("the name's gnuplot command never ran (no MARKER: ${markers})" NOT markers)
if(GNUPLOT)
  expect_true("the plot is drawn" EXISTS "${hostile_out}/radius.png")
  expect_true("the --out with an apostrophe gets its plots" EXISTS "${WORK}/hostile/it's out/radius.png" AND EXISTS "${WORK}/hostile/it's out/pareto.png")
endif()
file(READ "${hostile_out}/sweep.csv" csv)
string(FIND "${csv}" "\n\"evil\nsystem \"\"touch MARKER\"\"\n#'\\\",rsm-radial," quoted_cell)
expect_true("sweep.csv holds the name as one quoted cell (RFC 4180)" quoted_cell GREATER -1)
file(READ "${hostile_out}/sweep.md" md)
string(FIND "${md}" "\n## evil system \"touch MARKER\" \\#'\\\\\n" heading)
expect_true("sweep.md shows the name as a one-line heading, escaped" heading GREATER -1)
# sweep.md's command, read back by a shell, gives the same words: the name is one word, not code.
string(REGEX MATCH "```sh\nvplkit sweep ([^`]*)\n```" command "${md}")
file(WRITE "${WORK}/hostile/words.sh" "printf '[%s]\\n' ${CMAKE_MATCH_1}\n")
execute_process(COMMAND sh "${WORK}/hostile/words.sh" WORKING_DIRECTORY "${WORK}/hostile" OUTPUT_VARIABLE words RESULT_VARIABLE code)
string(FIND "${words}" "[--scene]\n[${evil}]\n" scene_word)
string(FIND "${words}" "[--out]\n[${hostile_out}]\n" out_word)
expect_true("sweep.md's command is the sweep's words for a shell (exit ${code})" code EQUAL 0 AND scene_word GREATER -1 AND out_word GREATER -1)
file(GLOB_RECURSE markers "${WORK}/*MARKER")
expect_true("reading sweep.md's command ran nothing (no MARKER: ${markers})" NOT markers)
execute_process(COMMAND ${hostile_sweep} --out "${hostile_out}" WORKING_DIRECTORY "${WORK}/hostile" RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(READ "${hostile_out}/sweep.csv" again)
expect_true("the sweep resumes from the CSV the name is quoted in, and adds nothing (${code}: ${err})"
            code EQUAL 0 AND out MATCHES "resuming .*2 row[(]s[)]" AND again STREQUAL csv)

# gnuplot's own reason when it draws nothing: a gnuplot that fails, and none on PATH.
file(MAKE_DIRECTORY "${WORK}/fakebin" "${WORK}/emptybin")
file(WRITE "${WORK}/fakebin/gnuplot" "#!/bin/sh\necho \"fake gnuplot: cannot open the pngcairo terminal\" >&2\nexit 3\n")
file(CHMOD "${WORK}/fakebin/gnuplot" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
expect_success("a failing gnuplot's reason is named" "no plot .*radius\\.png: gnuplot failed \\(exit status 3\\): fake gnuplot: cannot open the pngcairo terminal"
               ${CMAKE_COMMAND} -E env "PATH=${WORK}/fakebin:$ENV{PATH}" "${VPLKIT}" sweep --technique rsm-radial ${tiny} --vary radius=0.125,0.5 --out "${WORK}/fake")
file(READ "${WORK}/fake/sweep.md" md)
expect_true("sweep.md names gnuplot's failure, not a missing gnuplot" md MATCHES "No radius[.]png: gnuplot failed" AND NOT md MATCHES "not installed")
expect_success("no gnuplot on PATH is named as such" "no plot .*radius\\.png: gnuplot is not installed"
               ${CMAKE_COMMAND} -E env "PATH=${WORK}/emptybin" "${VPLKIT}" sweep --technique rsm-radial ${tiny} --vary radius=0.125,0.5 --out "${WORK}/none")

# --- the grid's size: counted without overflow, bounded before it is planned -------------------
set(values "")
foreach(i RANGE 1 256)
  list(APPEND values ${i})
endforeach()
string(JOIN "," values ${values})
set(axes "")
foreach(name size rsm-size indirect-divisor radius paths samples-per-path min-radius rotation-jitter)
  list(APPEND axes --vary "${name}=${values}")
endforeach()
expect_usage_error("8 axes of 256 values: 2^64 configurations, counted, not wrapped to 0"
                   "the grid has about 1\\.84e\\+19 configurations \\(size \\(256\\) x rsm-size \\(256\\) x .*\\), more than --max-configurations 100000"
                   "${WORK}/g1" "${VPLKIT}" sweep --technique rsm-radial ${axes} --out "${WORK}/g1")
set(thousand "")
foreach(i RANGE 1 1000)
  list(APPEND thousand ${i})
endforeach()
list(SUBLIST thousand 0 200 two_hundred)
string(JOIN "," thousand ${thousand})
string(JOIN "," two_hundred ${two_hundred})
expect_usage_error("400,000 configurations are refused before they are planned"
                   "the grid has 400000 configurations \\(radius \\(2\\) x paths \\(1000\\) x samples-per-path \\(200\\)\\), more than --max-configurations 100000"
                   "${WORK}/g2" "${VPLKIT}" sweep --technique rsm-radial --vary radius=0.1,0.2 --vary "paths=${thousand}" --vary "samples-per-path=${two_hundred}"
                   --out "${WORK}/g2")
expect_usage_error("--max-configurations is a positive count" "--max-configurations: Value 0 not in range" "${WORK}/g3"
                   "${VPLKIT}" sweep --technique rsm-radial --vary radius=0.1,0.2 --max-configurations 0 --out "${WORK}/g3")
expect_usage_error("--max-configurations 2 refuses 3" "the grid has 3 configurations \\(radius \\(3\\)\\), more than --max-configurations 2" "${WORK}/g4"
                   "${VPLKIT}" sweep --technique rsm-radial --vary radius=0.1,0.2,0.3 --max-configurations 2 --out "${WORK}/g4")
expect_success("--max-configurations 3 plans 3" "3 configuration\\(s\\)"
               "${VPLKIT}" sweep --technique rsm-radial --vary radius=0.1,0.2,0.3 --max-configurations 3 --plan --out "${WORK}/g4")

# --- one sweep at a time in a folder: the second, started while the first holds the folder's lock,
# is refused and writes nothing; the first's rows are whole; run again, it adds its own. -----------
execute_process(COMMAND sh -c "\"$0\" sweep --technique rsm-radial --size 24 --rsm-size 32 --repeat 150 --min-rounds 150 --vary radius=0.125,0.25 --out \"$1\" >\"$2/first.txt\" 2>&1 & first=$!
                               i=0; while [ ! -e \"$1/.vplkit-sweep.lock\" ] && [ $i -lt 500 ]; do sleep 0.02; i=$((i + 1)); done
                               \"$0\" sweep --technique rsm-radial --size 24 --rsm-size 32 --repeat 1 --min-rounds 1 --vary radius=0.5,0.75 --out \"$1\" >\"$2/second.txt\" 2>&1
                               second=$?; wait $first; echo \"$? $second\""
                        "${VPLKIT}" "${WORK}/both" "${WORK}"
                OUTPUT_VARIABLE codes OUTPUT_STRIP_TRAILING_WHITESPACE)
file(READ "${WORK}/second.txt" second)
expect_true("two concurrent sweeps into one --out: the first exits 0, the second 1 (${codes}): ${second}"
            codes STREQUAL "0 1" AND second MATCHES "another vplkit sweep is writing to .*both [(]it holds .*[.]vplkit-sweep[.]lock[)]")
read_rows("${WORK}/both/sweep.csv" rows)
list(LENGTH rows count)
expect_true("the first sweep's 2 rows, none of the second's" count EQUAL 3 AND rows MATCHES "rsm-radial,0[.]125," AND NOT rows MATCHES "rsm-radial,0[.](5|75),")
expect_true("the lock is gone with its holder" NOT EXISTS "${WORK}/both/.vplkit-sweep.lock")
expect_success("the second sweep, run again, adds its rows" "resuming .*2 row\\(s\\)"
               "${VPLKIT}" sweep --technique rsm-radial --size 24 --rsm-size 32 --repeat 1 --min-rounds 1 --vary radius=0.5,0.75 --out "${WORK}/both")
read_rows("${WORK}/both/sweep.csv" rows)
list(LENGTH rows count)
expect_true("4 rows: both sweeps' whole" count EQUAL 5)

# --- render --stats ----------------------------------------------------------------------------
expect_success("render --stats with a reference" "quality against rsm-brute-force.*rel_rmse.*wrote .*stats\\.json"
               "${VPLKIT}" render --technique rsm-alg6 --scene occluder --size 24 --rsm-size 32 --reference rsm-brute-force --stats "${WORK}/stats.json"
               --out "${WORK}/stats.png")
file(READ "${WORK}/stats.json" json)
string(JSON radius GET "${json}" settings radius)
string(JSON slots GET "${json}" settings slots)
string(JSON method GET "${json}" timing method)
string(JSON first_pass GET "${json}" timing every_pass passes 0 pass)
string(JSON rel_rmse GET "${json}" quality rel_rmse)
expect_true("the JSON holds the settings in effect, the passes with their method and the quality"
            radius EQUAL 0.75 AND slots EQUAL 8 AND method MATCHES "wall clock|timer queries" AND first_pass STREQUAL "RSM generation" AND rel_rmse GREATER 0)
expect_failure("--stats must be .json" "--stats must name a \\.json file" "${WORK}/stats2*"
               "${VPLKIT}" render --size 16 --stats "${WORK}/stats2.txt" --out "${WORK}/stats2.png")
expect_failure("--samples without --reference monte-carlo" "--samples is read by --reference monte-carlo, not by --reference none" "${WORK}/stats3*"
               "${VPLKIT}" render --size 16 --samples 4 --out "${WORK}/stats3.png")

cli_report()
