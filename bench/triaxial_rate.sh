# The triaxial deck's shearing rate and time step, read from examples/triaxial/in.triaxial
# (its `variable erate index` and `timestep` lines), and the axial strain after D shearing
# steps by the deck's own rule (the platen moves D steps of erate H0 dt from H0, so
# eps_a = -ln(1 - D erate dt)) -- for the scripts that drive the deck (specimen.sh,
# analysis_cost.sh). Sourced, not run: sets erate and dt, defines shear_strain.
triaxial_deck=$(cd "$(dirname "${BASH_SOURCE[0]}")/../examples/triaxial" && pwd)/in.triaxial
erate=$(sed -n 's/^variable *erate index *\([0-9.eE+-]*\).*/\1/p' "$triaxial_deck")
dt=$(sed -n 's/^timestep *\([0-9.eE+-]*\).*/\1/p' "$triaxial_deck")
[ -n "$erate" ] && [ -n "$dt" ] ||
  { echo "triaxial_rate.sh: no erate or timestep in $triaxial_deck" >&2; exit 1; }

# shear_strain D [FORMAT]: eps_a after D shearing steps, printed with FORMAT (default %.12g)
shear_strain() {
  awk -v s="$1" -v r="$erate" -v dt="$dt" -v f="${2:-%.12g}" \
    'BEGIN { printf f, -log(1 - s * r * dt) }'
}
