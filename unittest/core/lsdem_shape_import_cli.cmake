# lsdem_shape_import_cli.cmake -- end-to-end runs of `lsdem-shape from-labels` and
# `lsdem-shape from-mesh` (cmake -P script).
#   cmake -DTOOL=<path to lsdem-shape> -DWORK=<scratch dir> -P lsdem_shape_import_cli.cmake
# Inputs are written here as text (OBJ) or as bytes 1..3 (a raw u8 label image with no
# background: CMake cannot write NUL bytes). Expectations are independent of the code:
# voxel counts and box centroids, closed-form cube volumes, the names of mesh defects.
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)

# ---- from-labels: a 12 x 6 x 6 u8 image, label 1 for x < 6, label 2 for x >= 6, and one
# voxel of label 3 at (11, 5, 5) (dropped below --min-voxels 2). Grain 1 is a 6-voxel cube,
# centroid at voxel (2.5, 2.5, 2.5); grain 2 the cube at x 6..11 less the corner voxel:
# 215 voxels, centroid ((216 * 8.5 - 11) / 215, (216 * 2.5 - 5) / 215, same) =
# (8.4884, 2.4884, 2.4884) voxels, times the voxel size 0.5 = (4.2442, 1.2442, 1.2442).
string(ASCII 1 one)
string(ASCII 2 two)
string(ASCII 3 three)
set(image "")
foreach(k RANGE 5)
  foreach(j RANGE 5)
    foreach(i RANGE 11)
      if(i EQUAL 11 AND j EQUAL 5 AND k EQUAL 5)
        string(APPEND image "${three}")
      elseif(i LESS 6)
        string(APPEND image "${one}")
      else()
        string(APPEND image "${two}")
      endif()
    endforeach()
  endforeach()
endforeach()
file(WRITE ${WORK}/labels.raw "${image}")
run(1 from-labels labels.raw labels.lslib --raw 12 6 6 u8 --voxel 0.5 --min-voxels 2
    --nodes 60 --data labels.data --density 2)
expect_in("${out}" "12 x 6 x 6 voxels, 2 grains, 1 label below 2 voxels dropped"
          "2 grid shapes" "in-situ sample, 2 grains")
file(READ ${WORK}/labels.data data)
# grain 2 (label 2): 1-based shape 2, density 2, centroid (4.2442, 1.2442, 1.2442)
string(REGEX MATCH "\n2 1 2 2 ([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+) " line "${data}")
if(NOT line)
  message(FATAL_ERROR "no Atoms line for grain 2 in:\n${data}")
endif()
# cmake has no floating-point math: compare in units of 1e-4 (tolerance 0.001 = 0.002 voxel)
foreach(pair "${CMAKE_MATCH_1};42442" "${CMAKE_MATCH_2};12442" "${CMAKE_MATCH_3};12442")
  list(GET pair 0 got)
  list(GET pair 1 want)
  string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9][0-9]).*$" "\\1\\2" got4 "${got}")
  math(EXPR diff "${got4} - ${want}")
  if(diff GREATER 10 OR diff LESS -10)
    message(FATAL_ERROR "grain 2 position ${got}, expected ${want}e-4")
  endif()
endforeach()
expect_in("${data}" "-0.25 5.75 xlo xhi" "2 atoms")
run(1 list labels.lslib)
expect_in("${out}" "label_1" "label_2")
run(0 from-labels labels.raw bad.lslib --raw 12 6 7 u8)
expect_in("${err}" "wrong dimensions or type")
run(0 from-labels labels.raw bad.lslib)
expect_in("${err}" "is not a TIFF file")
run(0 from-labels no-such.tif bad.lslib)              # a missing file is named as such
expect_in("${err}" "cannot open no-such.tif")
run(0 from-mesh . bad.lslib)                          # a folder is not a mesh file
expect_in("${err}" "not a regular file")

# ---- from-mesh: a 2 x 2 x 2 OBJ cube (volume 8), the same without one face (open), and
# two overlapping cubes (self-intersecting).
set(cube_v "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n")
set(cube_f "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 1 5 8 4\n")
file(WRITE ${WORK}/cube.obj "${cube_v}${cube_f}")
run(1 from-mesh cube.obj cube.lslib --spacing 0.1 --nodes 100 --scale 0.5 --name c)
expect_in("${out}" "12 triangles, mesh volume 1," "grid shape 'c', 100 nodes")
file(WRITE ${WORK}/open.obj "${cube_v}f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n")
run(0 from-mesh open.obj open.lslib)
expect_in("${err}" "not closed" "4 boundary edges" "--allow-open")
run(1 from-mesh open.obj open.lslib --allow-open --nodes 50)
expect_in("${err}" "warning")
set(shifted "v -0.5 -0.7 -0.4\nv 1.5 -0.7 -0.4\nv 1.5 1.3 -0.4\nv -0.5 1.3 -0.4\n")
string(APPEND shifted "v -0.5 -0.7 1.6\nv 1.5 -0.7 1.6\nv 1.5 1.3 1.6\nv -0.5 1.3 1.6\n")
file(WRITE ${WORK}/two.obj "${cube_v}${cube_f}${shifted}f 9 12 11 10\nf 13 14 15 16\n"
           "f 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\nf 9 13 16 12\n")
run(0 from-mesh two.obj two.lslib --allow-open)
expect_in("${err}" "intersects itself")
