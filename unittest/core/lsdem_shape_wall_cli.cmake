# lsdem_shape_wall_cli.cmake -- end-to-end runs of `lsdem-shape wall` and `terrain` (cmake -P).
#   cmake -DTOOL=<path to lsdem-shape> -DWORK=<scratch dir> -P lsdem_shape_wall_cli.cmake
# A good input writes its band file and exits 0; a bad one exits 1 naming the problem and
# writes nothing; a usage error exits 2.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)

# run_rc(rc ARGS...): the exit status must be rc exactly. Sets out and err.
function(run_rc want)
  execute_process(COMMAND ${TOOL} ${ARGN} WORKING_DIRECTORY ${WORK}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL want)
    message(FATAL_ERROR "lsdem-shape ${ARGN}: exit ${rc}, expected ${want}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_no_file name)
  if(EXISTS ${WORK}/${name})
    message(FATAL_ERROR "${name} was written by a failed run")
  endif()
  file(GLOB tmp ${WORK}/${name}.tmp*)
  if(tmp)
    message(FATAL_ERROR "a failed run left ${tmp}")
  endif()
endfunction()

# a closed cube [0, 1]^3 (outward faces), and the same without its top
set(cube_v "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n")
string(CONCAT cube_sides "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\n"
                        "f 3 8 7\nf 4 1 5\nf 4 5 8\n")
file(WRITE ${WORK}/cube.obj "${cube_v}${cube_sides}f 5 6 7\nf 5 7 8\n")
file(WRITE ${WORK}/open.obj "${cube_v}${cube_sides}")

run_rc(0 wall cube.obj cube.band --spacing 0.05)
expect_in("${out}" "cube.obj: 12 triangles, 0 degenerate (zero area), 0 duplicate, 0 open edges"
  "width 0.1 (2 h)" "stored bricks:" "build time:" "surface check: max |phi| at the 8 vertices"
  "ridges and slots narrower than 2 h (0.1): 0" "cube.band: band file of a closed mesh")
if(NOT EXISTS ${WORK}/cube.band)
  message(FATAL_ERROR "wall: cube.band not written")
endif()
run_rc(0 wall cube.obj scaled.band --spacing 0.1 --width 0.3 --scale 2)
expect_in("${out}" "width 0.3 (3 h)")
# a cube without its top: a mesh with holes, signed by winding number -- but the hole (a
# whole face) is far wider than the band: refused naming where; with --closed refused as open
run_rc(1 wall open.obj open.band --spacing 0.05)
expect_in("${out}" "10 triangles" "4 open edges" "signed near its holes by the generalised winding number")
expect_in("${err}" "the mesh's holes are too wide to close")
expect_no_file(open.band)
run_rc(1 wall open.obj open.band --spacing 0.05 --closed)
expect_in("${err}" "lsdem-shape: wall: open.obj: mesh is not closed: 4 boundary edges"
  "needs a closed surface (--closed)")
expect_no_file(open.band)
run_rc(1 wall missing.obj x.band --spacing 0.05)
expect_in("${err}" "missing.obj: cannot open")
run_rc(1 wall cube.obj x.band --spacing 0.05 --width 0.01)
expect_in("${err}" "width 0.01 is below the spacing h = 0.05")
expect_no_file(x.band)
run_rc(2 wall cube.obj x.band)
expect_in("${err}" "--spacing H is required")
run_rc(2 wall cube.obj x.band --spacing 0.05 --cell 1)
run_rc(2 wall cube.obj)

# terrain from an ESRI ASCII grid (one nodata height)
set(asc_head "ncols 4\nnrows 3\nxllcorner 10\nyllcorner 20\ncellsize 1\nNODATA_value -9999\n")
file(WRITE ${WORK}/good.asc "${asc_head}1 2 3 4\n2 -9999 4 5\n3 4 5 6\n")
run_rc(0 terrain good.asc good.band --spacing 0.25)
expect_in("${out}" "good.asc: 4 x 3 heights, cell 1, first at (10.5, 20.5), heights 1 .. 6, 1 nodata"
  "padded by 2 cells of edge heights" "surface: 76 triangles" "width 0.5 (2 h)"
  "good.band: band file of a terrain")
if(NOT EXISTS ${WORK}/good.band)
  message(FATAL_ERROR "terrain: good.band not written")
endif()
file(WRITE ${WORK}/bad.asc "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2 3 4\n")
run_rc(1 terrain bad.asc bad.band --spacing 0.25)
expect_in("${err}" "lsdem-shape: terrain: bad.asc: line 5: unknown header key 'celsize'")
expect_no_file(bad.band)
file(WRITE ${WORK}/short.asc "${asc_head}1 2 3 4\n2 3\n")
run_rc(1 terrain short.asc short.band --spacing 0.25)
expect_in("${err}" "short.asc: line 8: the file ends after 6 of the ncols x nrows = 4 x 3 = 12 values")
expect_no_file(short.band)
file(WRITE ${WORK}/word.asc "${asc_head}1 2 3 4\n2 3 4 5\n3 4 five 6\n")
run_rc(1 terrain word.asc word.band --spacing 0.25)
expect_in("${err}" "word.asc: line 9: 'five' is not a number")
expect_no_file(word.band)
run_rc(1 terrain good.asc x.band --spacing 0.25 --cell 2)
expect_in("${err}" "an ASCII grid gives its cell size")
run_rc(1 terrain good.xyz x.band --spacing 0.25)
expect_in("${err}" "unknown height-map format")
expect_no_file(x.band)
# kept as heights: no holes, the raster's own spacing
file(WRITE ${WORK}/full.asc "${asc_head}1 2 3 4\n2 3 4 5\n3 4 5 6\n")
run_rc(0 terrain full.asc full.band --heights)
expect_in("${out}" "padded by 4 cells" "heights: 12 x 11 columns at spacing 1, width 2 (2 h)"
  "surface check: max |phi| at the 132 columns' vertices 0 h"
  "full.band: band file of a terrain's heights")
run_rc(1 terrain good.asc holes.band --heights)
expect_in("${err}" "is nodata: a terrain kept as heights has no holes")
expect_no_file(holes.band)
run_rc(2 terrain full.asc x.band --heights --spacing 0.5)
expect_in("${err}" "--heights keeps the raster's own spacing")
# an output path that is a folder is refused and left as it was
file(MAKE_DIRECTORY ${WORK}/folder.band)
run_rc(1 terrain good.asc folder.band --spacing 0.25)
expect_in("${err}" "exists and is not a regular file")
if(NOT IS_DIRECTORY ${WORK}/folder.band)
  message(FATAL_ERROR "folder.band was replaced")
endif()
message(STATUS "lsdem-shape wall/terrain CLI: all checks passed")
