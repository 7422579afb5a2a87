#!/usr/bin/env bash
# The flange sector of cases/flange-sector-cyclic refined for issue 47's
# benchmark (>= 300k dofs on 2 ranks): the mesh written by the case's own
# generator at refinement K (flange.py --refine K: K = 5 gives 384,033 dofs),
# the case run unchanged on it under MPI, and optionally the 3D frictionless
# block of about the same size (cases/block-3d --refine 5, 394,848 dofs) for
# the time per Newton iteration against it. Prints Newton iterations per
# increment (largest and mean), cutbacks, seconds per Newton iteration
# (assembly + solve from summary.json: start-up, event searches' output and
# writing do not count), peak memory and bytes per dof.
# Needs the parallel build: cargo build --release --features parallel
# Usage: BIN=<parallel build> benches/flange-sector.sh [K=5] [ranks=2] [-- asperity run options]
#   (e.g. -- --stop-after 8: the first 8 increments, the tightening to t = 0.4)
#   BLOCK=5 also runs cases/block-3d --refine 5 --increments 2 on as many ranks;
#   PETSC_OPTS="..." passes options to PETSc; OUT=dir keeps runs apart.
set -euo pipefail
cd "$(dirname "$0")/.."
k=${1:-5}
ranks=${2:-2}
shift $(( $# < 2 ? $# : 2 ))
[ "${1:-}" = "--" ] && shift
extra=("$@")
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=${BIN:-./target/release/asperity}
out=${OUT:-target/flange-sector}/k$k-n$ranks
rm -rf "$out"
mkdir -p "$out/case"
python3 cases/flange-sector-cyclic/flange.py --refine "$k" > "$out/case/flange.msh"
cp cases/flange-sector-cyclic/case.toml "$out/case/"
# shellcheck disable=SC2086
# exit code 3: stopped by --stop-after N with its partial results (a shorter benchmark)
rc=0
mpirun -n "$ranks" $bin run "$out/case" --quiet --out "$out/run" "${extra[@]}" -- ${PETSC_OPTS:-} \
    > "$out/log.txt" 2>&1 || rc=$?
[ "$rc" = 0 ] || [ "$rc" = 3 ] || { tail -20 "$out/log.txt"; exit 1; }
summary() {
    python3 - "$1" "$2" <<'PY'
import csv, json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
its = [int(r["iterations"]) for r in csv.DictReader(open(sys.argv[1] + "/curve.csv"))]
work = s["solve_seconds"] + s["assembly_seconds"]
mem = s["peak_memory_mb"]
print(f"| {sys.argv[2]} | {s['dofs']:,} | {s['backend']} | {s['ranks']} | {s['increments']} | "
      f"{max(its)} | {sum(its) / len(its):.2f} | {s['cutbacks']} | {s['newton_iterations']} | "
      f"{s['wall_seconds']:.1f} | {work / s['newton_iterations']:.2f} | {mem:,.0f} | "
      f"{mem * 1048576 / s['dofs']:,.0f} |")
PY
}
echo "| run | dofs | backend | ranks | increments | Newton its, largest | mean | cutbacks | Newton its | wall (s) | s per Newton it | peak MB | bytes/dof |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
summary "$out/run" "flange-sector-cyclic, flange.py --refine $k"
if [ -n "${BLOCK:-}" ]; then
    # shellcheck disable=SC2086
    mpirun -n "$ranks" $bin run cases/block-3d --refine "$BLOCK" --increments 2 --quiet --out "$out/block" -- ${PETSC_OPTS:-} >/dev/null
    summary "$out/block" "block-3d --refine $BLOCK (frictionless, no interface)"
fi
