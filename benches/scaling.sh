#!/usr/bin/env bash
# Mesh-refinement series of cases/punch-plane-stress-fine for the serial faer
# backend and PETSc (MUMPS LU) on 1 and 2 MPI ranks. Prints a Markdown table.
# Needs the parallel build: cargo build --release --features parallel
# Usage: benches/scaling.sh "2 4 8 12" [max refine for serial]
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-"2 4 8 12"}
serial_max=${2:-8}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
bin=./target/release/asperity
out=target/scaling
mkdir -p "$out"
field() { python3 -c "import json,sys; d=json.load(open('$1')); v=d; [v:=v[k] for k in '$2'.split('.')]; print(v)"; }
echo "| refine | dofs | backend | ranks | increments | Newton its | KSP its | wall (s) | solve (s) | assembly (s) | peak memory (MB) | bytes/dof |"
echo "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for r in $levels; do
    runs=("petsc 1" "petsc 2")
    [ "$r" -le "$serial_max" ] && runs=("serial 1" "${runs[@]}")
    for run in "${runs[@]}"; do
        set -- $run
        dir="$out/r$r-$1-$2"
        if [ "$1" = serial ]; then
            $bin run cases/punch-plane-stress-fine --refine "$r" --backend serial --quiet --out "$dir" >/dev/null
        else
            mpirun -n "$2" $bin run cases/punch-plane-stress-fine --refine "$r" --quiet --out "$dir" >/dev/null
        fi
        s="$dir/summary.json"
        dofs=$(field "$s" dofs)
        mem=$(field "$s" peak_memory_mb)
        ksp=$( [ "$1" = serial ] && echo "-" || field "$s" backend_stats.ksp_iterations )
        printf "| %s | %s | %s | %s | %s | %s | %s | %.1f | %.1f | %.1f | %.0f | %.0f |\n" "$r" "$dofs" "$1" "$2" \
            "$(field "$s" increments)" "$(field "$s" newton_iterations)" "$ksp" "$(field "$s" wall_seconds)" \
            "$(field "$s" solve_seconds)" "$(field "$s" assembly_seconds)" "$mem" "$(python3 -c "print($mem*1048576/$dofs)")"
    done
done
