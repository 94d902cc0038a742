#!/usr/bin/env bash
# Virtual triaxial test: make the grains, pack them in a mould, put the membrane on,
# consolidate and shear (in.triaxial), plot. Called by `./lsdem example triaxial` (which sets
# LSDEM_LMP and LSDEM_SHAPE_TOOL). Environment knobs:
#   SHAPES=angular (default: random sand-like grains) | spheres (equal-volume spheres,
#   the report's §3.4.4 control); NP=2 ranks; NGRAINS=300; MU=0.6; OUT=out (or out/spheres);
#   EPSMAX (final axial strain); CYCLES=N unload-reload cycles (default none; CYC_AT, CYC_STEP,
#   CYC_AMP, CYC_Q, CYC_HOLD: in.triaxial's cyc_* variables; plot.py --cycles draws them); KM, KM_OUTER
#   (membrane springs); PIVOT=1 (the top platen pivots about the ram contact point, report
#   §3.2.1; OUT default out/pivot); STRIDE=N (grain contacts test every N-th node, forces
#   times N, report §3.4.1; default 1); DENSITY=dense (default: packed frictionless in the
#   mould, in.prepare, the densest packing of these grains) | loose (packed at the test's
#   friction, MU_PREP=0.6: the loosest); E_TARGET=e: packed from MU_PREP=0.6 with the
#   friction lowered step by step until the void ratio in the mould is e (OUT out/e<e>);
#   NODES (surface nodes per grain, default: lsdem-shape's mean spacing 0.09 d, inside the
#   report's d/10 rule), SPACING (grid spacing, default 1.0 px: R/10 for the smallest
#   grains); NSHAPES (random shapes, default 8); ANGULARITY (of the random shapes, default
#   0.12; 0.05: rounder, like the report's eroded low-resolution avatars); R (specimen radius, default 90 px for 300
#   grains, scaled as NGRAINS^(1/3)); KM scales with R (10 at R = 90); PACK_SEED (seed of the
#   random loose packing, default 3: another seed, another specimen of the same grains).
# Then plot.py (the CSV's curves) and figures.py (the figure pack, report Figures 3.12-3.25,
# in $OUT/figures).
# `run.sh prepare` stops when the inputs of in.triaxial are made (examples/make_inputs.sh).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-2}
n=${NGRAINS:-300}
kind=${SHAPES:-angular}
mu=${MU:-0.6}
pivot=${PIVOT:-0}
out=${OUT:-$here/out$([ "$kind" = spheres ] && echo /spheres || true)$([ "${DENSITY:-dense}" = loose ] && echo /loose || true)${E_TARGET:+/e$E_TARGET}$([ "$pivot" != 0 ] && echo /pivot || true)}
# specimen radius (pixels): 90 for 300 grains of ~31 px (D/d ~ 6), scaled as NGRAINS^(1/3) so that
# the packed specimen stays about twice as high as wide
R=${R:-$(awk -v n="$n" 'BEGIN { printf "%d", 90 * (n / 300)^(1/3) + 0.5 }')}
density=${DENSITY:-dense}
case "$density" in
  dense) mu_prep=${MU_PREP:-0}; densify=1 ;;   # frictionless compaction: the densest packing
  loose) mu_prep=${MU_PREP:-0.6}; densify=0 ;; # jammed at the test's friction: the loosest
  *) echo "run.sh: DENSITY is dense or loose" >&2; exit 2 ;;
esac
# a void ratio in between: from MU_PREP (default 0.6) the friction is lowered until e <= E_TARGET
[ -n "${E_TARGET:-}" ] && { mu_prep=${MU_PREP:-0.6}; densify=1; }
nodes=${NODES:+--nodes $NODES}
spacing=${SPACING:-1.0}
rho=2.65e-3   # scaled grain density (see in.triaxial)
rb=10         # membrane sphere radius (report Table 3.2), outer layer 1.1 rb
km=${KM:-$(awk -v r="$R" 'BEGIN { printf "%.3g", 10 * r / 90 }')}  # membrane spring stiffness K_nbb = K_sbb: the report's 50 N/m (Table 3.2) is for a
              # specimen of radius 500 px; the hoop springs of a membrane shrunk by a radial strain
              # e push outward with a stress ~ K e / R, so this R = 90 specimen keeps the report's
              # share of sigma_c with K = 50 * 90/500 ~ 10 (K = 50 here: sigma_r ~ 0.8 sigma_c)
km_outer=${KM_OUTER:-$(awk -v r="$R" 'BEGIN { printf "%.3g", 2 * r / 90 }')}  # the outer layer only covers the inner layer's gaps and passes its 20 %
              # share of the pressure inward; stiff hoop springs there hold part of that share back.
              # Softer still (KM=4 KM_OUTER=1) and the outer layer is pressed through the inner
              # one's gaps onto the grains; that membrane fails at ~3% axial strain.
enter_out "$out"
mpi_for "$np"
start=$SECONDS

mode=${1:-}   # prepare: stop when the inputs are made; resume: go on from triaxial.restart
if [ "$mode" != resume ]; then
# 1. grains: NSHAPES (default eight) random sand-like shapes, ~31 px, ~450 nodes each (mean node spacing 0.09 d,
#    the report's d/10 rule; lsdem-shape warns on standard error when a shape breaks it); or
#    spheres of the same volumes and node count (level-set grids, so they roll like grains)
rm -f grains.lslib rand.lslib sph*.lslib ball_*.lslib all.lslib
"$shape" random rand.lslib --count "${NSHAPES:-8}" --size 31 --size-spread 0.15 --elongation 0.75 \
  --flatness 0.75 --angularity "${ANGULARITY:-0.12}" --roughness 0.02 --seed 5 $nodes --spacing "$spacing" >shapes.log
if [ "$kind" = spheres ]; then
  parts=()
  # `list` columns: index name kind grid h= nodes clusters radius volume I1 I2 I3
  while read -r idx nn vol; do
    r=$(awk -v v="$vol" 'BEGIN { printf "%.6g", (3 * v / (4 * 3.141592653589793))^(1/3) }')
    "$shape" analytic "sph$idx.lslib" sphere "$r" --nodes "${NODES:-$nn}" --spacing "$spacing" \
      --name "sphere$idx" >>shapes.log
    parts+=("sph$idx.lslib")
  done < <("$shape" list rand.lslib | awk '$3 == "grid" { print $1, $6, $9 }')
  "$shape" merge grains.lslib "${parts[@]}" >/dev/null
  rm -f sph*.lslib rand.lslib
else
  mv rand.lslib grains.lslib
fi
nshapes=$("$shape" list grains.lslib | awk '$3 == "grid"' | wc -l)

# 2. random loose packing in a tall cylinder (solid fraction ~0.3), then packed in a rigid mould
#    to the requested density (in.prepare: low-friction compaction)
hpack=$(awk -v n="$n" -v r="$R" 'BEGIN { printf "%d", 720 * n / 300 * (90 / r)^2 }')
# deposition: grains fall at ~20 px/time (gravity 1, damping 0.05) and the platen follows at up
# to 25 px/time, so the steps grow with the packing's height
nprep=${NPREP:-$(awk -v h="$hpack" 'BEGIN { print (6 * h > 6000 ? int(6 * h) : 6000) }')}
"$shape" pack grains.lslib packed.data --count "$n" --cylinder "$((R - 2))" "$hpack" --density "$rho" --seed "${PACK_SEED:-3}"
"${mpi[@]}" "$lmp" -in "$here/in.prepare" -var lib grains.lslib -var data packed.data -var R "$R" \
  -var sigma_prep 0.2 -var nprep "$nprep" -var damp_prep 0.05 -var mu_prep "$mu_prep" -var densify "$densify" -var e_target "${E_TARGET:-0}" \
  -var mu_final "$mu" -var rho "$rho" -log log.prepare -echo none -screen none
H=$(awk '/^PREPARED/ { print $3 }' log.prepare)
echo "packed: $(grep '^PREPARED' log.prepare)"
sed '/^Velocities/,$d' sample.data > sample_grains.data   # grains at rest
# the void ratio measured independently, on a lattice with the grains' level sets: the whole
# mould and its core, one grain diameter (31 px) away from the walls' looser layer
{ echo "mould $("$shape" voids grains.lslib sample_grains.data --cylinder "$R" 0 "$H")"
  echo "core $("$shape" voids grains.lslib sample_grains.data --cylinder "$R" 0 "$H" --inset 31)"
} > voids.txt
echo "void ratio: $(awk '{ printf "%s e = %s   ", $1, $10 }' voids.txt)(lattice measure, voids.txt)"

# 3. the membrane (double layer, spheres rb and 1.1 rb) around the packed grains
"$shape" analytic ball_in.lslib sphere "$rb" --analytic >/dev/null
"$shape" analytic ball_out.lslib sphere "$(awk -v r=$rb 'BEGIN { print 1.1 * r }')" --analytic >/dev/null
"$shape" merge all.lslib grains.lslib ball_in.lslib ball_out.lslib >/dev/null
"$shape" membrane mem --radius "$R" --height "$H" --z0 0 --rb "$rb" --library all.lslib \
  --shapes $((nshapes + 1)) $((nshapes + 2)) --types 2 3 --grains sample_grains.data \
  --density "$rho" --knbb "$km" --ksbb "$km" --kouter "$km_outer" "$km_outer"
[ "$mode" = prepare ] && exit 0
fi

# 4. consolidation and shearing; `run.sh resume` (same OUT and knobs, a larger EPSMAX) goes on
#    shearing a finished run from its end state, triaxial.restart, to EPSMAX (log.2.lammps,
#    triaxial.2.csv; triaxial_joined.csv joins the two parts)
log=log.lammps part=()
if [ "$mode" = resume ]; then
  [ -f triaxial.restart ] && [ -f shear_state.in ] && [ ! -f triaxial.2.csv ] || {
    echo "run.sh resume: $out needs a finished run (triaxial.restart, shear_state.in) not resumed yet" >&2; exit 1; }
  log=log.2.lammps part=(-var resume triaxial.restart -var part .2)
fi
echo "running lmp on $np rank(s): $kind grains, mu $mu (log in $out/$log)"
rm -f "$log"
"${mpi[@]}" "$lmp" -in "$here/in.triaxial" -var lib all.lslib -var data mem.data \
  -var memin mem.in -var memtri mem.tri -var mu "$mu" -var pivot "$pivot" -var rho "$rho" -var R "$R" \
  -var stride "${STRIDE:-1}" \
  ${EPSMAX:+-var epsmax $EPSMAX} \
  ${CYCLES:+-var cycles $CYCLES} ${CYC_AT:+-var cyc_at $CYC_AT} ${CYC_STEP:+-var cyc_step $CYC_STEP} \
  ${CYC_AMP:+-var cyc_amp $CYC_AMP} ${CYC_Q:+-var cyc_q $CYC_Q} ${CYC_HOLD:+-var cyc_hold $CYC_HOLD} "${part[@]}" \
  -log "$log" -echo none -screen none &
lmp_pid=$!
# the deck's PROGRESS lines (strain reached, time left) on the screen as the log grows
tail --pid=$lmp_pid -n +1 -F "$log" 2>/dev/null | grep --line-buffered '^PROGRESS' \
  | sed -u 's/^PROGRESS /  /' || true
wait $lmp_pid
grep -E '^(PIVOT|CONSOLIDATED|CYCLE|RESUMED|SHEARED)' "$log"
echo "total time $((SECONDS - start)) s"
csv=triaxial.csv
if [ "$mode" = resume ]; then
  /usr/bin/python3 "$here/compare.py" --join triaxial.csv triaxial.2.csv > triaxial_joined.csv
  csv=triaxial_joined.csv
fi
/usr/bin/python3 "$here/plot.py" "$csv" "$kind"
if [ -n "${CYCLES:-}" ] && [ "$mode" != resume ]; then
  /usr/bin/python3 "$here/plot.py" --cycles cycles.csv
  echo "cycles: $out/cycles.csv, $out/cycles.png (report Figure 3.25), $out/loops.csv"
fi
/usr/bin/python3 "$here/figures.py" .   # the figure pack: out/figures/ (README.md)
echo "results: $out/triaxial.csv, $out/q_eps.png, $out/phi_eps.png, $out/epsv_eps.png, $out/dump.triaxial"
