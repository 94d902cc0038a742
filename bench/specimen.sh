#!/usr/bin/env bash
# The report's production specimen on this machine (PEER 2022/06 §3.5: ~20,000 CT grains with
# ~750 nodes each, in a flexible membrane): build a cylindrical specimen of N random sand-like
# grains, pack it dense (examples/triaxial/in.prepare, frictionless compaction), put the
# triaxial example's double-layer membrane on, and time consolidation and a shearing segment
# (examples/triaxial/in.triaxial, same parameters and strain rate), or the whole test to 15 %.
#
#   bench/specimen.sh [OUTDIR] [options]         (after ./lsdem build; OUTDIR default
#                                                 bench/out/specimen-<grains>-<variant>)
#     --grains N      grains (default 20000)
#     --shapes K      distinct random shapes (default 2000)
#     --unique        one shape per grain: grain i uses library entry i, its own copy of its
#                     template's grid and nodes (the CT case, where every grain is unique and
#                     the grids no longer fit in cache); same specimen as without --unique
#     --nodes M       surface nodes per shape (default 750), --spacing H grid spacing (1.0 px)
#     --size D        median equivalent diameter (default 31 px, as the triaxial example)
#     --np P          MPI ranks for the lmp runs (default 2)
#     --cons S        consolidation steps (default 8000, as in.triaxial)
#     --shear S       shearing steps timed (default 2000); --full: shear to --epsmax (0.15)
#     --jobs J        parallel lsdem-shape processes making the shapes (default 1; each
#                     process has its own seed, so the cached library depends on J)
#     --resume        with --full: go on with an interrupted --full run in OUTDIR from its
#                     newest readable checkpoint (in.triaxial writes one every 2000 shearing
#                     steps: shear.a.restart, shear.b.restart; else consolidated.restart);
#                     each resumed part logs to log.rK.lammps and its CSV rows to
#                     triaxial.rK.csv; triaxial_full.csv joins them
# Environment: LSDEM_BUILD_DIR (default ./build), LSDEM_HOME (cache, default ~/.cache/lsdem):
# shapes and the prepared (packed) specimen are cached under $LSDEM_HOME/bench/specimen/ and
# reused by later runs with the same grains, shapes, nodes, spacing, size and seed.
#
# With --full also specimen.png: phi and eps_v against eps_a with the report's values, and the
# peak, dilatancy and critical-state figures of examples/triaxial/compare.py; and the figure
# pack of report Figures 3.12-3.25 in OUTDIR/figures/ (examples/triaxial/figures.py on the
# snapshots in.triaxial takes at 5, 10, 15 %: fields, force chains, band grains, fabric).
# Prints the time split (shapes, packing, preparation, membrane, consolidation, shearing, and
# LAMMPS's Pair/Bond/Neigh/Comm/Modify split of the shearing run), the workload per grain-step
# (compute pair lsdem), memory (LAMMPS's own per-rank figure at the start of shearing, and the
# ranks' anonymous and file-backed resident memory, sampled from /proc every 2 s), and last:
#   us_per_grain_step=<x> node_tests_per_s=<y> mem_per_grain_bytes=<z> bytes_per_shape=<w>
# (z: the ranks' anonymous memory while shearing less that of the same ranks with no atoms,
# per grain; w: the library's bytes per grain shape, the memory a shape takes once touched)
#   projected_s_to_15pct=<t> [actual_s_to_15pct=<a>]
# (a: the wall time of the parts' LAMMPS runs, steps redone after an interruption included)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
top=$here/..
ex=$top/examples/triaxial
build=${LSDEM_BUILD_DIR:-$top/build}
lmp=${LSDEM_LMP:-$build/lmp}
shape=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
home=${LSDEM_HOME:-$HOME/.cache/lsdem}

grains=20000 shapes=2000 unique=0 nodes=750 spacing=1.0 size=31 np=2 cons=8000 shear=2000
full=0 epsmax=0.15 jobs=1 seed=11 resume=0 outdir=
while [ $# -gt 0 ]; do
  case "$1" in
    --grains) grains=$2; shift ;;
    --shapes) shapes=$2; shift ;;
    --unique) unique=1 ;;
    --nodes) nodes=$2; shift ;;
    --spacing) spacing=$2; shift ;;
    --size) size=$2; shift ;;
    --np) np=$2; shift ;;
    --cons) cons=$2; shift ;;
    --shear) shear=$2; shift ;;
    --full) full=1 ;;
    --epsmax) epsmax=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --seed) seed=$2; shift ;;
    --resume) resume=1 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    -*) echo "specimen.sh: unknown option $1 (--help)" >&2; exit 2 ;;
    *) [ -z "$outdir" ] || { echo "specimen.sh: one OUTDIR only" >&2; exit 2; }; outdir=$1 ;;
  esac
  shift
done
for v in grains shapes nodes np cons shear jobs seed; do
  [[ ${!v} =~ ^[0-9]+$ ]] && [ "${!v}" -gt 0 ] || { echo "specimen.sh: --$v wants a positive integer" >&2; exit 2; }
done
[ -x "$lmp" ] && [ -x "$shape" ] || { echo "specimen.sh: no lmp/lsdem-shape in $build (./lsdem build)" >&2; exit 1; }
[ "$resume" = 0 ] || [ "$full" = 1 ] || { echo "specimen.sh: --resume goes with --full" >&2; exit 2; }
variant=$([ "$unique" = 1 ] && echo unique || echo "k$shapes")
outdir=${outdir:-$here/out/specimen-$grains-$variant}
mkdir -p "$outdir"
outdir=$(cd "$outdir" && pwd)
cd "$outdir"
mpi=()
[ "$np" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$np")
say() { printf '%s\n' "$*" | tee -a summary.txt; }
[ "$resume" = 1 ] || : > summary.txt
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# the triaxial example's geometry, scaled (run.sh): radius 90 px for 300 grains of 31 px, as
# N^(1/3); membrane springs 10 and 2 at R = 90, scaled with R; density, membrane spheres
R=$(awk -v n="$grains" -v d="$size" 'BEGIN { printf "%d", 90 * (n / 300)^(1/3) * d / 31 + 0.5 }')
rho=2.65e-3 rb=10
km=$(awk -v r="$R" 'BEGIN { printf "%.3g", 10 * r / 90 }')
kmo=$(awk -v r="$R" 'BEGIN { printf "%.3g", 2 * r / 90 }')
hpack=$(awk -v n="$grains" -v r="$R" -v d="$size" 'BEGIN { printf "%d", 720 * n / 300 * (90 / r)^2 * (d / 31)^3 }')
say "specimen: $grains grains, $shapes random shapes ($([ "$unique" = 1 ] && echo "one library entry per grain" || echo "shared templates")), $nodes nodes, grid $spacing px, d $size px; R $R px; $np rank(s)"

# ---- 1. shapes (cached) ------------------------------------------------------------------
cache=$home/bench/specimen/v1-k$shapes-n$nodes-h$spacing-d$size-s$seed
mkdir -p "$cache"
t0=$(now)
if [ ! -f "$cache/shapes.lslib" ]; then
  echo "making $shapes random shapes ($nodes nodes, $jobs job(s); cached in $cache)" >&2
  per=$(( (shapes + jobs - 1) / jobs )) parts=() pids=()
  for ((j = 0; j < jobs; j++)); do
    cnt=$(( shapes - j * per < per ? shapes - j * per : per ))
    [ "$cnt" -gt 0 ] || break
    "$shape" random "$cache/part$j.lslib" --count "$cnt" --size "$size" --size-spread 0.15 \
      --elongation 0.75 --flatness 0.75 --angularity 0.12 --roughness 0.02 --seed $((seed + 7919 * j)) \
      --nodes "$nodes" --spacing "$spacing" >"$cache/part$j.log" 2>&1 &
    pids+=($!) parts+=("$cache/part$j.lslib")
  done
  for p in "${pids[@]}"; do wait "$p"; done
  "$shape" merge "$cache/shapes.tmp.lslib" "${parts[@]}" >/dev/null
  mv "$cache/shapes.tmp.lslib" "$cache/shapes.lslib"
  cat "$cache"/part*.log | grep -c 'warning' > "$cache/warnings.txt" || true
  rm -f "${parts[@]}"
fi
t_shapes=$(secs "$t0" "$(now)")
say "shapes: $("$shape" list "$cache/shapes.lslib" | awk '$3 == "grid" { n++; nd += $6 } END { printf "%d shapes, mean %.0f nodes", n, nd / n }'); library $(du -m "$cache/shapes.lslib" | cut -f1) MB; $t_shapes s (0 when cached)"

# ---- 2. packing and preparation (cached): RSA in a tall cylinder, then in.prepare ----------
spec=$cache/N$grains
mkdir -p "$spec"
t0=$(now)
if [ ! -f "$spec/sample_grains.data" ]; then
  echo "packing $grains grains (cached in $spec)" >&2
  (cd "$spec" && "$shape" pack "$cache/shapes.lslib" packed.data --count "$grains" \
     --cylinder "$((R - 2))" "$hpack" --density "$rho" --seed 3 > pack.log 2>&1) || true
  cat "$spec/pack.log"
  tp=$(now)
  (cd "$spec" && "${mpi[@]}" "$lmp" -in "$ex/in.prepare" -var lib "$cache/shapes.lslib" \
     -var data packed.data -var R "$R" -var sigma_prep 0.2 -var nprep "$((6 * hpack > 6000 ? 6 * hpack : 6000))" -var damp_prep 0.05 \
     -var mu_prep 0 -var densify 1 -var mu_final 0.6 -var rho "$rho" \
     -log log.prepare -echo none -screen none)
  echo "$(secs "$tp" "$(now)")" > "$spec/prepare_seconds.txt"
  echo "$(secs "$t0" "$tp")" > "$spec/pack_seconds.txt"
  sed '/^Velocities/,$d' "$spec/sample.data" > "$spec/sample_grains.data"
fi
H=$(awk '/^PREPARED/ { print $3 }' "$spec/log.prepare")
placed=$(awk '/ atoms$/ { print $1; exit }' "$spec/sample_grains.data")
[ "$placed" = "$grains" ] || say "note: the random packing placed $placed of $grains grains (pack.log); figures are per placed grain"
grains=$placed
say "packed: $(grep '^PREPARED' "$spec/log.prepare" | cut -c10-)"
say "packing $(cat "$spec/pack_seconds.txt") s, preparation $(cat "$spec/prepare_seconds.txt") s on $np rank(s) (when made; cached since)"
[ -f "$spec/voids.txt" ] || "$shape" voids "$cache/shapes.lslib" "$spec/sample_grains.data" \
  --cylinder "$R" 0 "$H" --inset "$size" > "$spec/voids.txt"
say "core void ratio (lattice, 1 d from the walls): $(awk '{ print $9 }' "$spec/voids.txt")"

# ---- 3. library of this variant, membrane ------------------------------------------------
t0=$(now)
if [ "$resume" = 1 ]; then
  [ -f mem.data ] && [ -f all.lslib ] && [ -f shear_state.in ] || {
    echo "specimen.sh: --resume: $outdir has no interrupted --full run (mem.data, all.lslib, shear_state.in)" >&2; exit 1; }
  ngs=$("$shape" list all.lslib | awk '$3 == "grid"' | wc -l); ngs=$((ngs - 2))
else
  "$shape" analytic ball_in.lslib sphere "$rb" --analytic >/dev/null
  "$shape" analytic ball_out.lslib sphere "$(awk -v r=$rb 'BEGIN { print 1.1 * r }')" --analytic >/dev/null
  if [ "$unique" = 1 ]; then
    # entry i of the grains' library is a copy of grain i's template; the data file's shape
    # column becomes i (each grain its own shape)
    awk '/^Atoms/ { on = 1; next } on && NF >= 11 { print $3 - 1 }' "$spec/sample_grains.data" > picks.txt
    "$shape" pick grains.lslib "$cache/shapes.lslib" picks.txt >/dev/null
    awk '/^Atoms/ { on = 1; print; next } on && NF >= 11 { $3 = ++k } { print }' \
      "$spec/sample_grains.data" > sample_grains.data
  else
    ln -sf "$cache/shapes.lslib" grains.lslib
    cp "$spec/sample_grains.data" sample_grains.data
  fi
  ngs=$("$shape" list grains.lslib | awk '$3 == "grid"' | wc -l)
  "$shape" merge all.lslib grains.lslib ball_in.lslib ball_out.lslib >/dev/null
  "$shape" membrane mem --radius "$R" --height "$H" --z0 0 --rb "$rb" --library all.lslib \
    --shapes $((ngs + 1)) $((ngs + 2)) --types 2 3 --grains sample_grains.data \
    --density "$rho" --knbb "$km" --ksbb "$km" --kouter "$kmo" "$kmo" > membrane.log
fi
t_mem=$(secs "$t0" "$(now)")
natoms=$(awk '/ atoms$/ { print $1; exit }' mem.data)
libbytes=$(stat -L -c %s all.lslib)
say "membrane: $((natoms - grains)) spheres; library of this run $((libbytes / 1048576)) MB for $ngs grain shapes; $t_mem s"

# ---- 4. consolidation and shearing, with a memory sampler -------------------------------
# memory of the ranks as the sum over them of Pss_Anon and Pss_File (smaps_rollup), every 2 s
sample_memory() { # PID-OF-RUN OUTFILE
  while kill -0 "$1" 2>/dev/null; do
    pids=$( { if [ "$np" -gt 1 ]; then pgrep -P "$1" -x lmp; else echo "$1"; fi; } 2>/dev/null || true)
    [ -n "$pids" ] && for p in $pids; do cat "/proc/$p/smaps_rollup" 2>/dev/null; done |
      awk -v t="$(date +%s)" '/^Pss_Anon:/ { a += $2 } /^Pss_File:/ { f += $2 } /^Rss:/ { r += $2 }
        END { if (r > 0) print t, a, f, r }' >> "$2"
    sleep 2
  done
}
# the baseline: the same ranks with LAMMPS and MPI started, the library mapped, no atoms
cat > in.baseline <<'DECK'
units           si
atom_style      lsdem library all.lslib
region          box block -1 1 -1 1 -1 1
create_box      1 box
shell           sleep 6
DECK
rm -f mem_baseline.txt
"${mpi[@]}" "$lmp" -in in.baseline -log log.baseline -echo none -screen none &
base_pid=$!
sleep 1
sample_memory "$base_pid" mem_baseline.txt
wait "$base_pid" || true
source "$here/triaxial_rate.sh"  # erate, dt and shear_strain, from the deck
if [ "$full" = 1 ]; then
  em=$epsmax
else
  em=$(shear_strain "$shear" %.9g)
fi
# a --full run checkpoints every 2000 shearing steps; --resume goes on from the newest
# checkpoint that LAMMPS can read (a run killed while writing one leaves it truncated)
resume_vars=() log=log.lammps
if [ "$full" = 1 ]; then resume_vars=(-var checkpoint 2000); fi
if [ "$resume" = 1 ]; then
  from=
  for f in $(ls -t shear.a.restart shear.b.restart 2>/dev/null) consolidated.restart; do
    printf 'read_restart %s\n' "$f" > in.check_restart
    if "$lmp" -in in.check_restart -log none -echo none -screen none >/dev/null 2>&1; then from=$f; break; fi
    echo "specimen.sh: checkpoint $f does not read; trying an older one" >&2
  done
  [ -n "$from" ] || { echo "specimen.sh: --resume: no readable checkpoint in $outdir" >&2; exit 1; }
  k=1; while [ -f "log.r$k.lammps" ]; do k=$((k + 1)); done
  log=log.r$k.lammps
  resume_vars+=(-var resume "$from" -var part ".r$k")
  say "resuming from $from ($(date -r "$from" '+%F %T')): part r$k, log $log"
else
  rm -f log.r*.lammps triaxial.r*.csv parts.txt
fi
rm -f "$log" mem_samples.txt
t0=$(now)
"${mpi[@]}" "$lmp" -in "$ex/in.triaxial" -var lib all.lslib -var data mem.data -var memin mem.in \
  -var memtri mem.tri -var mu 0.6 -var rho "$rho" -var R "$R" -var ncons "$cons" -var epsmax "$em" \
  "${resume_vars[@]}" -log "$log" -echo none -screen none &
run_pid=$!
echo "$log $t0" >> parts.txt
sample_memory "$run_pid" mem_samples.txt &
sampler=$!
tail --pid=$run_pid -n +1 -F "$log" 2>/dev/null | grep --line-buffered '^PROGRESS' \
  | sed -u 's/^PROGRESS /  /' >&2 || true
wait "$run_pid"
wait "$sampler" 2>/dev/null || true
grep -E '^(CONSOLIDATED|RESUMED|SHEARED)' "$log" | tee -a summary.txt
if [ "$full" = 1 ]; then
  # the parts' CSV rows joined: an earlier part's rows up to the step its successor resumed
  # from (that part's first row, which the successor repeats with fresh interval averages)
  /usr/bin/python3 "$ex/compare.py" --join triaxial.csv $(ls -v triaxial.r*.csv 2>/dev/null) > triaxial_full.csv
  # phi and eps_v against eps_a with the report's values marked (compare.py reads the
  # packing's core void ratio from voids.txt next to the CSV)
  echo "core $(cat "$spec/voids.txt")" > voids.txt
  /usr/bin/python3 "$ex/compare.py" specimen.png "$grains grains=triaxial_full.csv" \
    --title "LSDEM, $grains grains of $shapes shapes x $nodes nodes, against PEER 2022/06 Figs 3.12-3.13" \
    | tee -a summary.txt
  t0=$(now)
  /usr/bin/python3 "$ex/figures.py" . --out figures > figures.log 2>&1 \
    || say "figures.py failed (figures.log)"
  say "figure pack: figures/ ($(secs "$t0" "$(now)") s); band and theories: figures/summary.txt"
fi

# ---- 5. figures ------------------------------------------------------------------------
/usr/bin/python3 - "$grains" "$np" "$erate" "$dt" "$full" "$libbytes" "$ngs" "$log" <<'EOF' | tee -a summary.txt
import math, os, re, sys, time
grains, np, erate, dt, full, libbytes, ngs, last = sys.argv[1:]
grains, np, full, libbytes, ngs = int(grains), int(np), int(full), int(libbytes), int(ngs)
erate, dt = float(erate), float(dt)


def loops_of(text):
    return [(float(m.group(1)), int(m.group(2))) for m in
            re.finditer(r"^Loop time of (\S+) on \d+ procs for (\d+) steps", text, re.M)]


# consolidation: the first run's first loop; shearing: the last part's last loop (the whole
# shearing run, or what was left of it after the newest checkpoint)
t_cons, n_cons = loops_of(open("log.lammps").read())[0]
log = open(last).read()
t_sh, n_sh = loops_of(log)[-1]
# parts (one unless resumed): wall time from each part's start to its log's last write
parts = [l.split() for l in open("parts.txt")] if os.path.exists("parts.txt") else []
t_parts = sum(os.path.getmtime(f) - float(t0) for f, t0 in parts if os.path.exists(f))
# LAMMPS's section split of the shearing run
tail = log[log.rfind("Loop time of"):]
split = {m.group(1): float(m.group(2)) for m in
         re.finditer(r"^(Pair|Bond|Neigh|Comm|Output|Modify|Other)\s*\|[^|]*\|\s*(\S+)", tail, re.M)}
# workload and contact state: thermo rows of the shearing run, columns c_work[1..9]
rows = []
blocks = log.split("\nStep ")
head, body = blocks[-1].split("\n", 1)
cols = ["Step"] + head.split()
for line in body.splitlines():
    w = line.split()
    if len(w) != len(cols):
        if line.startswith("Loop time"):
            break
        continue
    try:
        rows.append([float(x) for x in w])
    except ValueError:
        pass
iw = [cols.index("c_work[%d]" % (k + 1)) if "c_work[%d]" % (k + 1) in cols else None for k in range(9)]
work = [sum(r[i] for r in rows) / len(rows) if rows and i is not None else float("nan") for i in iw]
mem = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = \S+ \| (\S+) \| \S+ Mbytes", log)
lmp_mb = float(mem[-1]) * np if mem else float("nan")
samples = [list(map(float, l.split())) for l in open("mem_samples.txt")] if \
    __import__("os").path.exists("mem_samples.txt") else []
anon = max((s[1] for s in samples), default=float("nan")) * 1024
filem = max((s[2] for s in samples), default=float("nan")) * 1024
base = [list(map(float, l.split())) for l in open("mem_baseline.txt")] if \
    __import__("os").path.exists("mem_baseline.txt") else []
anon0 = max((s[1] for s in base), default=0.0) * 1024
us = t_sh / (grains * n_sh) * 1e6
steps15 = math.ceil((1.0 - math.exp(-0.15)) / (erate * dt))
proj = t_cons + steps15 * t_sh / n_sh
print("consolidation: %d steps in %.1f s; shearing: %d steps in %.1f s (%.3f ms per step)"
      % (n_cons, t_cons, n_sh, t_sh, 1e3 * t_sh / n_sh))
print("shearing split: " + ", ".join("%s %.1f%%" % (k, 100 * v / t_sh) for k, v in split.items()))
print("workload per step: %.0f pairs within bounding spheres, %.0f contacting pairs, %.0f node "
      "lookups, %.0f penetrating nodes (%.1f lookups per grain-step)"
      % (work[0], work[1], work[2], work[3], work[2] / grains))
print("contact state (pair_style's history store): %.2f KB per grain in use, %.2f KB reserved "
      "(both pools as allocated); held per grain: %.1f pair states (80-byte list heads), %.1f "
      "node-list entries (64 bytes against grid grains), %.1f shear entries (56 bytes)"
      % (work[8] / grains / 1024, work[4] / grains / 1024, work[5] / grains, work[6] / grains,
         work[7] / grains))
print("memory: LAMMPS's own %.0f MB (%d ranks x per-rank average at the start of shearing) = "
      "%.2f KB per grain; resident anonymous %.0f MB, of which %.0f MB LAMMPS and MPI with no "
      "atoms: %.2f KB per grain of state, history, neighbour lists and the membrane; "
      "file-backed (the library's touched pages and the binary, shared) %.0f MB; library "
      "%.0f MB = %.0f KB per distinct shape"
      % (lmp_mb, np, lmp_mb * 1048576 / grains / 1024, anon / 1048576, anon0 / 1048576,
         (anon - anon0) / grains / 1024, filem / 1048576, libbytes / 1048576,
         libbytes / ngs / 1024))
print("projected time to 15%% axial strain (%d steps at the example's strain rate) plus "
      "consolidation: %.0f s = %.2f h on %d rank(s)" % (steps15, proj, proj / 3600, np))
extra = ""
if full:
    m = re.search(r"^SHEARED eps_a (\S+)", log, re.M)
    extra = " actual_s_to_%s=%.0f" % ("eps%.3f" % float(m.group(1)) if m else "end", t_parts)
    if len(parts) > 1:
        print("%d parts (resumed %d times); wall time of the parts %.0f s, steps redone after "
              "interruptions included" % (len(parts), len(parts) - 1, t_parts))
print("us_per_grain_step=%.3f node_tests_per_s=%.4g mem_per_grain_bytes=%.0f bytes_per_shape=%.0f "
      "projected_s_to_15pct=%.0f%s" % (us, work[2] * n_sh / t_sh, (anon - anon0) / grains, libbytes / ngs,
                                        proj, extra))
EOF
