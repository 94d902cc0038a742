# lsdem_shape_cli.cmake -- end-to-end run of the lsdem-shape tool (cmake -P script).
#   cmake -DTOOL=<path to lsdem-shape> -DWORK=<scratch dir> -P lsdem_shape_cli.cmake
# Expectations are closed forms: sphere R=2 has volume 4/3 pi 8 = 33.5103; ellipsoid
# 3 2 1 has 4/3 pi 6 = 25.1327, a grid of 2a/h + 1 + 2*3 margin samples per axis at the
# default spacing h = 1/10 of the smallest semi-axis, and 25132.7 in voxel units of 0.1.
file(MAKE_DIRECTORY ${WORK})

include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)

run(1 analytic s.lslib sphere 2 --analytic --nodes 50 --name ball)
run(1 analytic e.lslib ellipsoid 3 2 1 --nodes 120)
run(1 merge m.lslib s.lslib e.lslib)
run(1 list m.lslib)
expect_in("${out}" "2 shapes" "ball" "sphere" "33.5103" "ellipsoid" "25.1327" "67x47x27 h=0.1")
run(1 verify m.lslib)
expect_in("${out}" "0 bad")
run(1 to-morph m.lslib 1 e.dat)
run(1 from-morph back.lslib e.dat)
run(1 list back.lslib)
expect_in("${out}" "1 shape" " e " "25132.7" "120")
run(0 to-morph m.lslib 0 x.dat)          # analytic sphere: no grid
run(0 to-morph m.lslib 2 x.dat)          # no such index
run(0 list missing.lslib)
run(0 analytic x.lslib cube 1)
# a flat box: the default node count (0.09 d spacing) would be 74468 nodes, minutes of
# placing; refused with the count, and built at once when --nodes is given
run(0 analytic x.lslib box 1 1 1e-4 --spacing 0.05)
expect_in("${err}" "gives 74468 nodes; give --nodes N")
run(1 analytic flat.lslib box 1 1 1e-4 --spacing 0.05 --nodes 100)
expect_in("${out}" "100 nodes")
run(0 analytic x.lslib sphere 1 --nodes 0)
expect_in("${err}" "--nodes 1..1000000")
run(0 from-morph x.lslib s.lslib)        # a library is not a morphology file
# superellipsoid, random grains, packing (shape_random.c, shape_pack.c): the count the
# tool reports is the number of Atoms lines it wrote
run(1 analytic se.lslib superellipsoid 1 0.8 0.6 0.5 0.5 --nodes 200)
expect_in("${out}" "grid shape 'superellipsoid'")
run(0 analytic x.lslib superellipsoid 1 1 1 3 1)     # exponent outside [0.1, 2]
run(1 random r.lslib --count 2 --size 1.0 --seed 5 --elongation 0.7 --flatness 0.9)
expect_in("${out}" "2 random grains" "elongation 0.700 (asked 0.700)" "flatness 0.900 (asked 0.900)")
run(1 pack e.lslib p.data --count 5 --box 20 20 20 --seed 3)
expect_in("${out}" "5 of 5 grains placed")
run(0 pack e.lslib x.data --count 5 --box 20 20 20 --cylinder 3 10)   # which container?
expect_in("${err}" "not both")
# render takes any non-zero quaternion, normalised as read_data does it
file(WRITE ${WORK}/q2.data "LAMMPS data file\n\n1 atoms\n1 atom types\n\n-5 5 xlo xhi\n"
  "-5 5 ylo yhi\n-5 5 zlo zhi\n\nAtoms # lsdem\n\n1 1 1 1.0 0 0 0 2 0 0 0\n")
run(1 render e.lslib q2.data q2.png --size 64 48)
expect_in("${out}" "1 grains")
file(STRINGS ${WORK}/p.data atoms REGEX "^[0-9]+ 1 1 ")
list(LENGTH atoms natoms)
if(NOT natoms EQUAL 5)
  message(FATAL_ERROR "pack: 5 grains reported, ${natoms} Atoms lines written")
endif()
run(1 pack e.lslib q.data --count 40 --box 8 6 3 --seed 3 --max-tries 200)
string(REGEX MATCH "([0-9]+) of 40 grains placed" placed "${out}")
file(STRINGS ${WORK}/q.data atoms REGEX "^[0-9]+ 1 1 ")
list(LENGTH atoms natoms)
if(NOT placed OR NOT natoms EQUAL CMAKE_MATCH_1 OR natoms GREATER_EQUAL 40)
  message(FATAL_ERROR "overfull pack: reported '${placed}', ${natoms} Atoms lines written")
endif()

# nets (shape_net.c): a 5 x 3 square net has 2*15 - 5 - 3 = 22 bonds; clamping side u0
# (3 balls) and v1 (5) clamps 7; refusals name the problem
run(1 net n --library s.lslib --shape 1 --rb 2 --spacing 5 --size 20 10 --lattice square --clamp u0,v1)
expect_in("${out}" "5 x 3 balls (7 clamped), 22 bonds" "atom IDs 1-15")
run(0 net x --library s.lslib --shape 1 --rb 1 --spacing 5)
expect_in("${err}" "must be an analytic sphere of radius 1")
run(0 net x --library s.lslib --shape 1 --rb 2 --spacing 5 --clamp u2)
expect_in("${err}" "bad clamp edges 'u2'")
run(0 net x --library s.lslib --shape 1 --rb 2 --spacing 5 --e1 1 0 0 --e2 2 0 0)
expect_in("${err}" "not parallel")
# a second net added to the first's data file: IDs 16-30, types 3 4, molecule 2, bond
# type 2; a group name LAMMPS could not take, and a membrane on a file with bonds, refused
run(1 net n2 --library s.lslib --shape 1 --rb 2 --spacing 5 --size 20 10 --lattice square --grains n.data --name second)
expect_in("${out}" "atom IDs 16-30, types 3 (free) 4 (clamped), molecule 2, bond type 2")
run(0 net x --library s.lslib --shape 1 --rb 2 --spacing 5 --grains n.data --name "a b")
expect_in("${err}" "bad name")
run(0 membrane x --radius 20 --height 10 --rb 2 --library s.lslib --shapes 1 1 --grains n.data)
expect_in("${err}" "has bonds")
run(0 pack e.lslib q.data --count 40 --box 8 6 3 --seed 3 --max-tries 200 --strict)
# morphology files a grain cannot use are refused naming the shape: 3 x 3 x 3 grids, one
# with no negative value (no solid: said before any other check or warning, here the grid
# spacing 1 coarser than R/10 of its volume 1), one whose centroid (line 3, grid
# coordinates) lies beyond the grid (x = 5 > 2)
string(REPEAT "1 " 27 positive)
file(WRITE ${WORK}/nosolid.dat "1\n0.4 0.4 0.4\n1 1 1\n1\n0.5 0 0\n1\n3 3 3\n${positive}\n")
run(0 from-morph x.lslib e.dat nosolid.dat)
expect_in("${err}" "from-morph: shape 1: nosolid.dat: line 8: no level-set value is negative: "
  "the grid has no solid voxel, so the file describes no grain")
if(err MATCHES "nosolid.dat: (grid|mean|node|zero)")
  message(FATAL_ERROR "from-morph nosolid.dat: a quality warning before the no-solid error:\n${err}")
endif()
string(REPEAT "1 " 13 half)
file(WRITE ${WORK}/offgrid.dat "1\n0.4 0.4 0.4\n5 1 1\n1\n0.5 0 0\n1\n3 3 3\n${half}-1 ${half}\n")
run(0 from-morph x.lslib offgrid.dat)
expect_in("${err}" "shape 0 ('offgrid'): its centroid" "grid coordinates (5, 1, 1), outside the grid")
# R/10 warning: a spacing of R/10 up to round-off is not coarse (R = 0.002 and 0.5 at the
# default and a given spacing of R/10); one just above it is, and the message tells them apart
foreach(args "0.002" "0.5;--spacing;0.05")
  run(1 analytic r10.lslib sphere ${args} --nodes 50)
  if(err MATCHES "coarser")
    message(FATAL_ERROR "sphere ${args}: a spacing of R/10 warned as coarse:\n${err}")
  endif()
endforeach()
run(1 analytic r10.lslib sphere 1 --spacing 0.1001 --nodes 50)
expect_in("${err}" "grid spacing 0.1001 is coarser than R/10 = 0.1 ")
# an output path that exists and is not a regular file (here a pipe; /dev/null as root) is
# refused, and left as it was: the library is written to a new file renamed onto the path
file(REMOVE ${WORK}/out.fifo)
execute_process(COMMAND mkfifo ${WORK}/out.fifo)
run(0 analytic out.fifo sphere 1 --nodes 50)
expect_in("${err}" "exists and is not a regular file")
execute_process(COMMAND test -p ${WORK}/out.fifo RESULT_VARIABLE still_fifo)
if(NOT still_fifo EQUAL 0)
  message(FATAL_ERROR "the pipe out.fifo was replaced")
endif()
# bands (tools/lsdem_bands.py's geometry; its results are checked by core.test_shearband and
# lmp.band_zones): a file that is not whole records, a missing one, bad values; no points
file(WRITE ${WORK}/odd.f64 "12345")
run(0 bands odd.f64 --tol 1 --min-length 6)
expect_in("${err}" "not a whole number of (zone, x, y, z) float64 records")
run(0 bands none.f64 --tol 1 --min-length 6)
expect_in("${err}" "cannot open none.f64")
run(0 bands odd.f64 --tol 0 --min-length 6)
expect_in("${err}" "--tol")
run(0 bands odd.f64 --min-length 6)
expect_in("${err}" "usage: lsdem-shape bands")
file(WRITE ${WORK}/empty.f64 "")
run(1 bands empty.f64 --tol 1 --min-length 6)
if(NOT out STREQUAL "")
  message(FATAL_ERROR "bands of no points printed: ${out}")
endif()
message(STATUS "lsdem-shape CLI: all checks passed")
