#!/usr/bin/env bash
# Mesh-refinement series of cases/punch-plane-stress-fine for the serial faer
# backend and PETSc (MUMPS LU by default) on 1 and 2 MPI ranks. Prints a
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
# REPEAT=n runs every point n times (one row each) and fits the median time of
# each point (single runs on a shared virtual machine spread by up to 30%).
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-"2 4 8 12"}
serial_max=${2:-8}
shift $(( $# < 2 ? $# : 2 ))
[ "${1:-}" = "--" ] && shift
extra=("$@")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=${BIN:-./target/release/asperity}
out=${OUT:-target/scaling}
mkdir -p "$out"
field() { python3 -c "import json,sys; d=json.load(open('$1')); v=d; [v:=v[k] for k in '$2'.split('.')]; print(v)"; }
echo "| refine | dofs | backend | ranks | increments | Newton its | KSP its | wall (s) | s per Newton it | Newton it / linear solve | peak memory (MB) | bytes/dof |"
echo "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
fits=()
for r in $levels; do
    runs=("petsc 1" "petsc 2")
    [ "$r" -le "$serial_max" ] && runs=("serial 1" "${runs[@]}")
    for run in "${runs[@]}"; do
        set -- $run
        times=()
        for rep in $(seq 1 "${REPEAT:-1}"); do
            dir="$out/r$r-$1-$2"
            [ "${REPEAT:-1}" -gt 1 ] && dir="$dir-$rep"
            if [ "$1" = serial ]; then
                $bin run cases/punch-plane-stress-fine --refine "$r" --backend serial --quiet --out "$dir" "${extra[@]}" >/dev/null || [ $? -eq 3 ]
            else
                # shellcheck disable=SC2086
                mpirun -n "$2" $bin run cases/punch-plane-stress-fine --refine "$r" --quiet --out "$dir" "${extra[@]}" -- ${PETSC_OPTS:-} >/dev/null 2>&1 || [ $? -eq 3 ]
            fi
            s="$dir/summary.json"
            python3 - "$s" "$r" "$1" "$2" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); r, be, n = sys.argv[2:5]
its = s["newton_iterations"]; wall = s["wall_seconds"]; solve = s["solve_seconds"]
work = solve + s["assembly_seconds"]
ksp = s["backend_stats"].get("ksp_iterations", "-")
ksp = "-" if be == "serial" else f"{ksp:.0f}"
mem = s["peak_memory_mb"]
print(f"| {r} | {s['dofs']} | {be} | {n} | {s['increments']} | {its} | {ksp} | {wall:.1f} | "
      f"{work/its:.3f} | {work/solve:.2f} | {mem:.0f} | {mem*1048576/s['dofs']:.0f} |")
PY
            times+=("$(python3 -c "import json; s=json.load(open('$s')); print((s['solve_seconds']+s['assembly_seconds'])/s['newton_iterations'])")")
        done
        median=$(printf '%s\n' "${times[@]}" | sort -g | python3 -c 'import sys; v=[float(l) for l in sys.stdin]; print(v[len(v)//2])')
        fits+=("$1-$2 $(field "$s" dofs) $median")
    done
done
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
