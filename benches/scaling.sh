#!/usr/bin/env bash
# Mesh-refinement series of cases/punch-plane-stress-fine (or CASE=cases/x)
# for the serial faer backend and PETSc (its default solver by size) on 1 and
# 2 MPI ranks. Prints a
# Markdown table and the fitted growth exponent of time per Newton iteration.
# Needs the parallel build: cargo build --release --features parallel
# Usage: benches/scaling.sh "2 4 8 12" [max refine for serial] [-- asperity run options]
#   whole runs:            benches/scaling.sh "2 4 8 12" 8 -- --increments 5
#   first increment only:  benches/scaling.sh "4 8 12 18 27" 0 -- --increments 5 --stop-after 1
# (--stop-after N ends the run after N increments with exit code 3, accepted here.)
# "s per Newton it" and "it / linear solve" use the assembly and solve times
# of summary.json, so start-up and output writing do not count.
# PETSC_OPTS="-ksp_type gmres -pc_type gamg" passes options to PETSc;
# BIN=path runs another build of asperity; OUT=dir keeps runs apart;
# CASE=cases/block-3d runs another case (the 3D series);
# REPEAT=n runs every point n times (one row each; the repeats alternate
# between 1 and 2 ranks) and fits the median time of each point; the 2-rank
# speed-up is the median of the n adjacent pairs (single runs on a shared
# virtual machine spread by up to 30%: benches/bandwidth.rs).
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-"2 4 8 12"}
serial_max=${2:-8}
shift $(( $# < 2 ? $# : 2 ))
[ "${1:-}" = "--" ] && shift
extra=("$@")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=${BIN:-./target/release/asperity}
case=${CASE:-cases/punch-plane-stress-fine}
out=${OUT:-target/scaling}
mkdir -p "$out"
field() { python3 -c "import json,sys; d=json.load(open('$1')); v=d; [v:=v[k] for k in '$2'.split('.')]; print(v)"; }
echo "| refine | dofs | backend | ranks | increments | Newton its | KSP its | wall (s) | s per Newton it | Newton it / linear solve | peak memory (MB) | bytes/dof |"
echo "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
fits=()
speedups=()
for r in $levels; do
    runs=("petsc 1" "petsc 2")
    [ "$r" -le "$serial_max" ] && runs=("serial 1" "${runs[@]}")
    declare -A times=()
    # repeats alternate between the runs, so that a shared host's drift
    # reaches every run alike
    for rep in $(seq 1 "${REPEAT:-1}"); do
        for run in "${runs[@]}"; do
            set -- $run
            dir="$out/r$r-$1-$2"
            [ "${REPEAT:-1}" -gt 1 ] && dir="$dir-$rep"
            if [ "$1" = serial ]; then
                $bin run "$case" --refine "$r" --backend serial --quiet --out "$dir" "${extra[@]}" >/dev/null || [ $? -eq 3 ]
            else
                # shellcheck disable=SC2086
                mpirun -n "$2" $bin run "$case" --refine "$r" --quiet --out "$dir" "${extra[@]}" -- ${PETSC_OPTS:-} >/dev/null 2>&1 || [ $? -eq 3 ]
            fi
            s="$dir/summary.json"
            python3 - "$s" "$r" "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); r, be, n = sys.argv[2:5]
if be == "petsc" and not (s["backend"].startswith("petsc") and s["ranks"] == int(n)):
    sys.exit(f"{sys.argv[1]}: ran on {s['backend']} with {s['ranks']} rank(s), not PETSc on {n}: "
             "this build has no PETSc backend (cargo build --release --features parallel; "
             "cargo bench rebuilds target/release/asperity without it)")
its = s["newton_iterations"]; wall = s["wall_seconds"]; solve = s["solve_seconds"]
work = solve + s["assembly_seconds"]
ksp = s["backend_stats"].get("ksp_iterations")
ksp = "-" if ksp is None else f"{ksp:.0f}"
mem = s["peak_memory_mb"]
print(f"| {r} | {s['dofs']} | {be} | {n} | {s['increments']} | {its} | {ksp} | {wall:.1f} | "
      f"{work/its:.3f} | {work/solve:.2f} | {mem:.0f} | {mem*1048576/s['dofs']:.0f} |")
PY
            times[$1-$2]+="$(python3 -c "import json; s=json.load(open('$s')); print((s['solve_seconds']+s['assembly_seconds'])/s['newton_iterations'])") "
            dofs=$(field "$s" dofs)
        done
    done
    for run in "${runs[@]}"; do
        set -- $run
        median=$(printf '%s\n' ${times[$1-$2]} | sort -g | python3 -c 'import sys; v=[float(l) for l in sys.stdin]; print(v[len(v)//2])')
        fits+=("$1-$2 $dofs $median")
    done
    # 2-rank speed-up: per repeat (adjacent runs), then the median
    speedups+=("$r $dofs ${times[petsc-1]}/ ${times[petsc-2]}")
    unset times
done
echo
printf '%s\n' "${speedups[@]}" | python3 -c '
import sys
for l in sys.stdin:
    head, two = l.split("/")
    r, n, *one = head.split(); two = two.split()
    q = sorted(float(a) / float(b) for a, b in zip(one, two))
    print(f"refine {r} ({n} dofs): 2-rank speed-up {q[len(q)//2]:.2f}"
          + (f" (median of {len(q)}: " + ", ".join(f"{x:.2f}" for x in q) + ")" if len(q) > 1 else ""))
'
printf '%s\n' "${fits[@]}" | python3 -c '
import sys, math, collections
d = collections.defaultdict(list)
for l in sys.stdin:
    k, n, t = l.split(); d[k].append((math.log(float(n)), math.log(float(t))))
for k, v in d.items():
    if len(v) < 2: continue
    mx = sum(x for x, _ in v) / len(v); my = sum(y for _, y in v) / len(v)
    b = sum((x - mx) * (y - my) for x, y in v) / sum((x - mx) ** 2 for x, _ in v)
    print(f"{k}: time per Newton iteration grows as N^{b:.2f}")
'
